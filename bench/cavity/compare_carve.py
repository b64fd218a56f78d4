#!/usr/bin/python3
"""Every goal on every mesh of ../shared/meshes, decided twice: by `offsetopt optimize` (its report's
`reachability`) and by the independent voxel programme ../shared/tools/reach/carve.py, run with the
tool's own wall, margin, ground tolerance, densities and sphere centre (the report's `parameters`).

carve.py reads the wall three ways (strict: the whole cell keeps it; mid: its centre does; loose:
some point of it may), which bracket what any void can do. A row agrees when
  - the tool calls the goal reachable and carve.py's loose reading does too (no reading of any void
    can then say it is out of reach), or
  - the tool proves it unreachable and carve.py's mid reading finds no void either,
and is "undecided" when the tool says it cannot tell (its two readings straddle the margin), with
what carve.py's readings say. Anything else is a disagreement.
For `stand` runs that exit 0 it also measures the fraction of the possible lowering of the centre of
mass that the written solid reaches, independently: the written STL's centre of mass by carve.py's
own exact moments, against carve.py's lowest centre of mass (--min-cz) on each reading.
Volume goals have no margin: the row compares the carvable volume only.

usage: /usr/bin/python3 bench/cavity/compare_carve.py [BINARY] [--meshes a.off,b.stl] [--goals stand,float]
         [--res N] [--no-min-cz] [--mesh-dir DIR]
The lowering fractions of the census (../shared/realposed, extracted by census.sh into OUT/meshes):
  compare_carve.py build/offsetopt --mesh-dir OUT/meshes --meshes cgal-data_dino.ply --goals stand
Prints one TSV row per case and a summary line; writes nothing else. Skips when ../shared is absent.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
SHARED = os.path.join(os.path.dirname(ROOT), 'shared')
CARVE = os.path.join(SHARED, 'tools', 'reach', 'carve.py')
MESHES = ['kitten_lowres.obj', 'rocker_arm.off', 'elephant.off', 'fertility.off', 'camel.off',
          'armadillo.off', 'horse.ply', 'Armadillo.ply', '20mm-xyz-cube.stl', 'hinge.stl',
          'spinit_kitten.obj', 'spinit_dolphin.obj']
GOALS = ['stand', 'stand-filled', 'roly-poly', 'spin', 'volume', 'float']


def goal_options(goal, volume):
    if goal == 'stand-filled':
        return ['--fill-density', '0.8']
    if goal == 'float':
        return ['--fluid-density', '0.8']
    if goal == 'volume':
        return ['--target-volume', repr(0.3 * volume)]
    return []


def written_cz_over_ground(stl):
    """The written solid's centre of mass over its lowest point, by carve.py's own mass code."""
    sys.path.insert(0, os.path.dirname(CARVE))
    from meshload import load
    import voxel
    V, T = load(stl)
    P = voxel.exact_moments(V, T)
    if P[0] < 0:
        P = -P
    return float(P[3] / P[0] - V[:, 2].min())


def tool_verdict(r):
    if r is None:
        return 'no report'
    if r.get('reachable'):
        return 'reachable'
    return 'unreachable' if r.get('decided') else 'undecided'


def agreement(verdict, carve):
    reach = {k: carve[k].get('reachable') for k in ('strict', 'mid', 'loose')}
    if verdict == 'reachable':
        return 'agree' if reach['loose'] else 'DISAGREE'
    if verdict == 'unreachable':
        return 'agree' if not reach['mid'] else 'DISAGREE'
    if verdict == 'undecided':
        # the tool's own bracket straddles the margin; any carve.py answer lies inside it
        said = {v for v in reach.values()}
        return 'undecided (carve.py: ' + ('split' if len(said) > 1 else 'reachable' if True in said
                                          else 'unreachable') + ')'
    return 'n/a'


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('binary', nargs='?', default=os.path.join(ROOT, 'build', 'offsetopt'))
    ap.add_argument('--meshes', default=','.join(MESHES))
    ap.add_argument('--mesh-dir', default=os.path.join(SHARED, 'meshes'),
                    help="where the meshes are (e.g. the census's posed meshes, extracted)")
    ap.add_argument('--goals', default=','.join(GOALS))
    ap.add_argument('--res', type=int, default=256, help="carve.py's cells along the longest side")
    ap.add_argument('--no-min-cz', action='store_true', help='skip the lowering fraction (the costly part)')
    a = ap.parse_args()
    if not os.path.isdir(a.mesh_dir):
        print(f'note: {a.mesh_dir} is absent; nothing to run')
        return 0
    work = tempfile.mkdtemp()
    counts = {}
    fractions = []
    print('mesh\tgoal\texit\ttool\ttool_margin\tcarve_strict\tcarve_mid\tcarve_loose\trow\tfraction_of_lowering'
          '\ttool_s\tcarve_s', flush=True)
    for mesh in a.meshes.split(','):
        path = os.path.join(a.mesh_dir, mesh)
        if not os.path.exists(path):
            continue
        info = json.loads(subprocess.run([a.binary, 'inspect', path, '--json', '-'], capture_output=True,
                                         text=True).stdout or '{}')
        for goal in a.goals.split(','):
            report, stl = os.path.join(work, 'r.json'), os.path.join(work, 's.stl')
            for f in (report, stl):
                if os.path.exists(f):
                    os.remove(f)
            start = time.time()
            code = subprocess.run([a.binary, 'optimize', path, '--goal', goal] +
                                  goal_options(goal, info.get('volume', 1.0)) +
                                  ['-o', stl, '--report', report, '--quiet', '--no-timings'],
                                  capture_output=True, timeout=1800).returncode
            tool_s = time.time() - start
            rep = json.load(open(report)) if os.path.exists(report) else {}
            reach, par = rep.get('reachability'), rep.get('parameters', {})
            verdict = tool_verdict(reach) if rep else 'no report'
            if code == 2 or not par:
                print(f'{mesh}\t{goal}\t{code}\t{verdict}\t-\t-\t-\t-\tn/a\t-\t{tool_s:.1f}\t-', flush=True)
                counts['n/a'] = counts.get('n/a', 0) + 1
                continue
            cmd = ['/usr/bin/python3', CARVE, path, goal, '--wall', repr(par['wall']), '--margin',
                   repr(par['margin']), '--ground-tol', repr(par['ground_tol'])]
            if par.get('fill_density') is not None:
                cmd += ['--fill-density', repr(par['fill_density'])]
            if par.get('fluid_density') is not None:
                cmd += ['--fluid-density', repr(par['fluid_density'])]
            centre = (rep.get('goal') or {}).get('sphere_center')
            if goal == 'roly-poly' and centre:
                cmd.append('--center=' + ','.join(repr(c) for c in centre))  # '=': a leading '-' is a value
            cmd += ['--res', str(a.res)]
            min_cz = goal == 'stand' and code == 0 and not a.no_min_cz
            if min_cz:
                cmd.append('--min-cz')
            start = time.time()
            out = subprocess.run(cmd, capture_output=True, text=True)
            carve_s = time.time() - start
            if out.returncode != 0:
                why = ' '.join(out.stderr.strip().splitlines()[-1:])
                print(f'{mesh}\t{goal}\t{code}\t{verdict}\t-\t-\t-\t-\tcarve failed: {why}\t-\t{tool_s:.1f}\t-',
                      flush=True)
                counts['carve failed'] = counts.get('carve failed', 0) + 1
                continue
            carve = json.loads(out.stdout.strip().splitlines()[-1])
            fraction = '-'
            if goal == 'volume':
                cells = [f"{carve[k]['carvable_volume']:.4g}" for k in ('strict', 'mid', 'loose')]
                row = 'n/a'
                tool_margin = f"{reach.get('carvable_volume') if reach else '-'}"
            else:
                cells = [f"{carve[k].get('reachable')}:{carve[k].get('best_margin')}"
                         for k in ('strict', 'mid', 'loose')]
                row = agreement(verdict, carve)
                tool_margin = f"{reach.get('best_margin')}/{reach.get('best_margin_upper')}"
                if min_cz and os.path.exists(stl):
                    start_cz = carve['input_cz_over_ground']
                    written = written_cz_over_ground(stl)
                    parts = {}
                    for k in ('strict', 'mid', 'loose'):
                        low = carve[k].get('min_cz_over_ground')
                        if low is not None and start_cz - low > 0:
                            parts[k] = (start_cz - written) / (start_cz - low)
                    fraction = '/'.join(f'{parts[k]:.3f}' if k in parts else '-'
                                        for k in ('strict', 'mid', 'loose'))
                    if 'mid' in parts:
                        fractions.append(parts['mid'])
            counts[row] = counts.get(row, 0) + 1
            # A verified solid is the tool's evidence where its programme could not tell (--outer).
            shown = verdict + (' (written solid)' if (reach or {}).get('evidence') == 'written solid' else '')
            print(f'{mesh}\t{goal}\t{code}\t{shown}\t{tool_margin}\t' + '\t'.join(cells) +
                  f'\t{row}\t{fraction}\t{tool_s:.1f}\t{carve_s:.1f}', flush=True)
    shutil.rmtree(work, ignore_errors=True)
    summary = ', '.join(f'{k} {v}' for k, v in sorted(counts.items()))
    print(f'compare_carve: {sum(counts.values())} cases; {summary}')
    if fractions:
        mids = sorted(fractions)
        print(f'compare_carve: stand, fraction of the possible lowering against carve.py mid: '
              f'min {mids[0]:.3f}, median {mids[len(mids) // 2]:.3f} over {len(mids)} runs')
    return 0


if __name__ == '__main__':
    sys.exit(main())
