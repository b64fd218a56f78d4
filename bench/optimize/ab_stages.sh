#!/usr/bin/env bash
# Two builds on the demo goals, run alternately (A, B, A, B, ...) with two threads: the median of
# each stage's seconds from the report's `timings` and of the wall clock, and the smallest wall
# clock. Alternating spreads the machine's changing load over both builds, and the medians of the
# stages show which stage a change moved, where a best-of-N of the total hides it. A figure, not a
# test; on the shared 2-core machine a difference under about 5% is noise.
#
# usage: bench/optimize/ab_stages.sh BINARY_A BINARY_B RUNS GOAL...
#   GOAL: a short name from bench/optimize/demo_goals.sh (stand filled top rolypoly buoy sphere)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
source "$root/bench/optimize/demo_goals.sh"
a=$(readlink -f "$1")
b=$(readlink -f "$2")
runs=$3
shift 3
meshes=$root/meshes
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for name in "$@"; do
  demo_goal_args "$name" "$meshes" || exit 2
  for ((i = 0; i < runs; ++i)); do
    for which in A B; do
      binary=$a
      [[ $which == B ]] && binary=$b
      rm -f "$out/o.stl" "$out/r.json"
      start=$(date +%s%N)
      "$binary" optimize "${args[@]}" -o "$out/o.stl" --report "$out/r.json" --quiet >/dev/null 2>&1
      end=$(date +%s%N)
      python3 -c 'import json, sys; t = json.load(open(sys.argv[1]))["timings"]; t["wall"] = int(sys.argv[2]) / 1e9; print(sys.argv[3], json.dumps(t))' \
        "$out/r.json" "$((end - start))" "$which" >>"$out/$name.log"
    done
  done
  python3 - "$name" "$out/$name.log" <<'EOF'
import json, statistics, sys
name, path = sys.argv[1], sys.argv[2]
rows = {"A": [], "B": []}
for line in open(path):
    which, text = line.split(" ", 1)
    rows[which].append(json.loads(text))
def median(which, key):
    return statistics.median([r.get(key) or 0.0 for r in rows[which]])
keys = [k for k, v in rows["A"][0].items() if isinstance(v, (int, float)) and median("A", k) > 0.01]
parts = [f"{k} {median('A', k):.3f}->{median('B', k):.3f}" for k in keys]
least = lambda which: min(r["wall"] for r in rows[which])
print(name, "  ".join(parts), f"| min wall {least('A'):.3f}->{least('B'):.3f}")
EOF
done
