#!/usr/bin/env bash
# Per-stage seconds and peak memory of `offsetopt optimize` for each goal on the demo meshes, on
# a generated 100k-vertex bottle and, when ../shared/meshes is present, on real meshes (a
# figure, not a test). Evaluations, the cavity written, the number of contours and the contoured
# cells of the last one are printed too: they explain the solve and contour times ("correct" is
# the verification of each contour and the re-solves between them).
# usage: bench/optimize/run.sh [BINARY]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
source "$root/bench/optimize/demo_goals.sh"
binary=${1:-$root/build/offsetopt}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

cases=()
for goal in "${demo_goals[@]}"; do cases+=("${goal#*|}"); done  # mesh|options
# About 100k vertices: the bottle sampled 5.5 times finer (101,730 vertices), a goal it can meet.
"$binary" generate bottle --detail 5.5 -o "$out/bottle100k.obj"
cases+=("$out/bottle100k.obj|--goal stand")
shared=$root/../shared/meshes
if [[ -d $shared ]]; then
  for m in armadillo.off horse.ply Armadillo.ply; do
    [[ -f $shared/$m ]] && cases+=("$shared/$m|--goal stand")
  done
else
  echo "note: ../shared/meshes is absent; demo meshes only"
fi

echo "machine: $(nproc) cores, load: $(cut -d' ' -f1-3 /proc/loadavg)"
printf '%-16s %-46s %6s %7s %7s %7s %7s %7s %7s %7s %8s %6s %7s %8s %9s %5s\n' mesh options verts skel basis solve verify contour correct total peakMB evals cavity contours cells exit
for c in "${cases[@]}"; do
  mesh=${c%%|*}; opts=${c#*|}
  [[ $mesh == /* ]] || mesh=$root/meshes/$mesh
  set +e
  /usr/bin/time -f '%M' -o "$out/mem" "$binary" optimize "$mesh" $opts -o "$out/solid.obj" --report "$out/r.json" --quiet 2>/dev/null
  code=$?
  set -e
  /usr/bin/python3 - "$out/r.json" "$out/mem" "$(basename "$mesh")" "$opts" "$code" <<'PY'
import json, sys
r = json.load(open(sys.argv[1])); t = r['timings']; mem = int(open(sys.argv[2]).read().split()[-1]) / 1024
c = r['cavity']; rounds = c.get('rounds', [])
cells = rounds[-1]['contoured_cells'] if rounds else 0
print(f"{sys.argv[3]:16} {sys.argv[4]:46} {r['vertices']:6d} {t['skeleton']:7.3f} {t['basis']:7.3f} {t['solve']:7.3f} "
      f"{t['verify']:7.3f} {t.get('contour', 0):7.3f} {t.get('correct', 0):7.3f} {t['total'] + t['load'] + t['write']:7.3f} "
      f"{mem:8.1f} {r['solver']['evaluations']:6d} {c['written']:>7} {len(rounds):8d} {cells:9d} {sys.argv[5]:>5}")
PY
done
