#!/usr/bin/env bash
# The measurement behind the defaults `--k 36 --basis mass`: every demo goal at several basis
# sizes with both bases. Prints per case whether the goal was met and verified, the objective
# (lower is better, comparable within one goal), evaluations and solve seconds, then a
# summary per (basis, k): cases met, total evaluations and seconds.
# usage: bench/optimize/defaults.sh [BINARY]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
source "$root/bench/optimize/demo_goals.sh"
binary=${1:-$root/build/offsetopt}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
cases=()
for goal in "${demo_goals[@]}"; do cases+=("${goal#*|}"); done  # mesh|options
printf '%-9s %3s %-14s %-44s %4s %10s %6s %7s\n' basis k mesh options met objective evals solve_s
for basis in mass laplacian; do
  for k in 16 24 36 48; do
    for c in "${cases[@]}"; do
      mesh=${c%%|*}; opts=${c#*|}
      set +e
      "$binary" optimize "$root/meshes/$mesh" $opts --k "$k" --basis "$basis" -o "$out/solid.ply" \
        --report "$out/r.json" --quiet 2>/dev/null
      set -e
      /usr/bin/python3 - "$out/r.json" "$basis" "$k" "$mesh" "$opts" <<'PY' | tee -a "$out/rows"
import json, sys
r = json.load(open(sys.argv[1]))
met = 'yes' if r['goal_met'] and r['valid'] else 'no'
print(f"{sys.argv[2]:9} {int(sys.argv[3]):3d} {sys.argv[4]:14} {sys.argv[5]:44} {met:>4} "
      f"{r['solver']['objective']:10.6f} {r['solver']['evaluations']:6d} {r['timings']['solve']:7.3f}")
PY
    done
  done
done
echo
/usr/bin/python3 - "$out/rows" <<'PY'
import collections, sys
summary = collections.OrderedDict()
for line in open(sys.argv[1]):
    f = line.split()
    key = (f[0], int(f[1]))
    s = summary.setdefault(key, [0, 0, 0, 0.0])
    s[0] += 1
    s[1] += f[-4] == 'yes'
    s[2] += int(f[-2])
    s[3] += float(f[-1])
print(f"{'basis':9} {'k':>3} {'met':>7} {'evals':>7} {'solve_s':>8}")
for (basis, k), (n, met, evals, secs) in summary.items():
    print(f"{basis:9} {k:3d} {met:3d}/{n:<3d} {evals:7d} {secs:8.3f}")
PY
