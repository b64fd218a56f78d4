#!/usr/bin/env bash
# Time and memory against the vertex count (issue 22): `offsetopt optimize --goal stand` on the
# bottle generated at several --detail values (10^4 to 10^6 vertices), one process each. Prints
# per run the stages of the report's `timings` (with two or more threads the coarse copy, then the
# basis and the skeleton, run beside the reachability programme, so they overlap), the solve's evaluations and seconds per evaluation, the end
# to end wall clock, the CPU seconds of all threads (user + system: less sensitive than the wall
# clock to other jobs on a shared machine) and the peak resident memory (/usr/bin/time %M), then a
# table of wall, CPU and peak memory against n with the local exponent between neighbouring sizes
# (log ratio over log n ratio). A figure, not a test: the load is printed beside it.
#
# usage: bench/optimize/scale.sh [BINARY] [DETAIL...]   (default details: 1.8 3.2 5.8 10 17.2)
#   THREADS=1 to run single-threaded; CALLGRIND=1 to add the instruction count of each run under
#   valgrind --tool=callgrind (slow: about 50 times the run; use it on one size at a time);
#   KEEP=DIR to keep each written solid and report as DIR/bottleD.stl and .json (for an
#   independent check such as ../shared/tools/validity).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
binary=${1:-$root/build/offsetopt}
shift || true
details=("$@")
[[ ${#details[@]} -gt 0 ]] || details=(1.8 3.2 5.8 10 17.2)
threads=${THREADS:-2}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), threads $threads"
printf '%-6s %8s %6s %6s %6s %6s %6s %6s %5s %7s %6s %6s %6s %6s %6s %7s %7s %8s %5s %s\n' \
  detail verts load coarse reach skel basis solve evals ms/eval verify contour correct quadric write wall cpu peakMB exit load_avg
for d in "${details[@]}"; do
  mesh=$out/bottle$d.obj
  "$binary" generate bottle --detail "$d" -o "$mesh"
  set +e
  /usr/bin/time -f '%e %M %U %S' -o "$out/time" "$binary" optimize "$mesh" --goal stand --threads "$threads" \
    -o "$out/solid.stl" --report "$out/r.json" --quiet 2>/dev/null
  code=$?
  set -e
  if [[ -n ${KEEP:-} ]]; then
    mkdir -p "$KEEP"
    cp "$out/solid.stl" "$KEEP/bottle$d.stl" 2>/dev/null || true
    cp "$out/r.json" "$KEEP/bottle$d.json" 2>/dev/null || true
  fi
  instructions=""
  if [[ ${CALLGRIND:-0} == 1 ]]; then
    valgrind --tool=callgrind --callgrind-out-file="$out/cg" "$binary" optimize "$mesh" --goal stand \
      --threads "$threads" -o "$out/solid2.stl" --report "$out/r2.json" --quiet >/dev/null 2>&1 || true
    instructions=$(callgrind_annotate "$out/cg" 2>/dev/null | awk '/PROGRAM TOTALS/ {gsub(",", "", $1); print $1}')
  fi
  /usr/bin/python3 - "$out/r.json" "$out/time" "$d" "$code" "$(cut -d' ' -f1 /proc/loadavg)" "$instructions" \
    "$out/rows" <<'PY'
import json, sys
report, timefile, detail, code, load, instructions, rows = sys.argv[1:8]
r = json.load(open(report)); t = r['timings']
wall, peak_kb, user, system = open(timefile).read().split()[-4:]
cpu = float(user) + float(system)
evals = r['solver']['evaluations']
line = (f"{detail:6} {r['vertices']:8d} {t['load']:6.2f} {t.get('coarse', 0):6.2f} {t.get('reach', 0):6.2f} {t['skeleton']:6.2f} {t['basis']:6.2f} "
        f"{t['solve']:6.2f} {evals:5d} {1000 * t['solve'] / max(evals, 1):7.2f} {t['verify']:6.2f} {t.get('contour', 0):6.2f} "
        f"{t.get('correct', 0):6.2f} {t.get('quadric', 0):6.2f} {t['write']:6.2f} {float(wall):7.2f} {cpu:7.2f} {int(peak_kb) / 1024:8.1f} "
        f"{code:>5} {load}")
if instructions: line += f"  {int(instructions) / 1e9:.1f} G instructions"
print(line)
open(rows, 'a').write(f"{r['vertices']} {wall} {cpu} {int(peak_kb) / 1024}\n")
PY
done
echo
echo "wall, CPU and memory against n (exponent: log of the ratio to the previous size over log of the n ratio)"
/usr/bin/python3 - "$out/rows" <<'PY'
import math, sys
rows = [tuple(map(float, l.split())) for l in open(sys.argv[1])]
print(f"{'vertices':>9} {'wall s':>7} {'cpu s':>7} {'peak MB':>8} {'wall exp':>8} {'cpu exp':>7} {'mem exp':>7}")
for i, (n, t, c, m) in enumerate(rows):
    te = ce = me = ''
    if i:
        pn, pt, pc, pm = rows[i - 1]
        scale = math.log(n / pn)
        te, ce, me = (f"{math.log(a / b) / scale:.2f}" for a, b in ((t, pt), (c, pc), (m, pm)))
    print(f"{int(n):9d} {t:7.2f} {c:7.2f} {m:8.1f} {te:>8} {ce:>7} {me:>7}")
PY
