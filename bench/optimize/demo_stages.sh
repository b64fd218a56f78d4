#!/usr/bin/env bash
# Instructions of the six demo goals and of their main stages: each goal once under valgrind
# --tool=callgrind with --threads 1 and STL output (deterministic, so usable on a busy machine),
# printing the total, the inclusive count of each main stage's function, and the sha256 prefix of
# the STL written (equal prefixes: the same solid). Slow: about 50 times a run.
#
# usage: bench/optimize/demo_stages.sh BINARY OUTDIR [stand filled top rolypoly buoy sphere]
#   OUTDIR keeps each goal's callgrind profile (NAME.out, for callgrind_annotate) and solid.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
source "$root/bench/optimize/demo_goals.sh"
binary=$(readlink -f "$1")
out=$2
shift 2
mkdir -p "$out"
meshes=$root/meshes
names=("$@")
if [[ ${#names[@]} -eq 0 ]]; then
  for goal in "${demo_goals[@]}"; do names+=("${goal%%|*}"); done
fi
stages='PROGRAM TOTALS|:offsetopt::(contour_cavity|verify_written_cavity|round_for_output|manifold_harmonics|reachability_stage|laplacian_contraction|self_intersections|verify_offsets|find_surface_defects|load_input|carvable_cells|write_quadric_void|offset_field|write_mesh)\(|OffsetSolve::run\(|TriangleBvh::TriangleBvh\('
for name in "${names[@]}"; do
  demo_goal_args "$name" "$meshes" || exit 2
  rm -f "$out/$name.stl" "$out/$name.out"
  valgrind --tool=callgrind --callgrind-out-file="$out/$name.out" "$binary" optimize "${args[@]}" \
    -o "$out/$name.stl" --quiet --threads 1 >/dev/null 2>&1 || true
  echo "== $name  $(sha256sum "$out/$name.stl" | cut -c1-16)"
  callgrind_annotate --inclusive=yes "$out/$name.out" 2>/dev/null | grep -E "$stages" |
    sed -E 's/ \([0-9. ]+%\) +/ /; s/\?\?\?:offsetopt::(\(anonymous namespace\)::)?//; s/\?\?\?://; s/\(.*//' |
    awk '{ printf "  %16s %s\n", $1, $2 }'
done
