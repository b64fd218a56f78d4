#!/usr/bin/env bash
# Every goal with --outer on every mesh of ../shared/meshes (horse first), keeping each written
# solid, then (when a CGAL validity binary is given) the independent pair count of the input and
# of every written solid. The table of docs/outer.md is this script's output.
# usage: bench/outer/outer_goals.sh BINARY OUTDIR [VALIDITY_BINARY] [EXTRA OPTIONS...]
#   MESHES (environment) overrides the list of meshes; GOALS (environment) picks goals by name.
#   BASELINE (environment): another binary run the same way (its exit code and pair count in two
#   more columns, its files under OUTDIR/baseline), to compare exit codes run by run.
#   TIMEOUT (environment): seconds per run, 900 unless given.
#   OUTDIR keeps <mesh>.<goal>.stl, .json and .err; VALIDITY_BINARY is ../shared/tools/validity built.
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
binary=$1
out=$2
validity=${3:-}
shift 3 || shift $#
shared=$root/../shared/meshes
[[ -d $shared ]] || { echo "note: ../shared/meshes is absent; nothing to run"; exit 0; }
mkdir -p "$out"
pairs() {  # self-intersecting pairs by the CGAL check, or - without it
  [[ -n $validity ]] || { echo -; return; }
  # validity exits 1 for a solid that is not valid: its count is still the answer (pipefail).
  { "$validity" "$1" 2>/dev/null || true; } |
    python3 -c "import json,sys; print(json.loads(sys.stdin.read())['self_intersecting_pairs'])" 2>/dev/null || echo '?'
}
baseline=${BASELINE:-}
limit=${TIMEOUT:-900}
[[ -n $baseline ]] && mkdir -p "$out/baseline"
printf 'mesh\tgoal\texit\tinput_pairs\tsolid_pairs\tseconds\treason%s\n' "${baseline:+$'\t'baseline_exit$'\t'baseline_pairs}"
meshes=${MESHES:-horse.ply kitten_lowres.obj rocker_arm.off elephant.off fertility.off camel.off armadillo.off \
  Armadillo.ply 20mm-xyz-cube.stl hinge.stl spinit_kitten.obj spinit_dolphin.obj}
for mesh in $meshes; do
  [[ -f $shared/$mesh ]] || continue
  volume=$("$binary" inspect "$shared/$mesh" --json - 2>/dev/null |
    python3 -c "import json,sys; print(json.load(sys.stdin)['volume'] * 0.3)" 2>/dev/null || echo 1)
  input_pairs=$(pairs "$shared/$mesh")
  for goal in "stand" "stand-filled --fill-density 0.8" "roly-poly" "spin" "volume --target-volume $volume" \
    "float --fluid-density 0.8"; do
    [[ -n ${GOALS:-} && " $GOALS " != *" ${goal%% *} "* ]] && continue
    name=$out/${mesh%.*}.${goal%% *}
    start=$(date +%s.%N)
    code=0
    timeout "$limit" "$binary" optimize "$shared/$mesh" --goal $goal --outer "$@" -o "$name.stl" --report "$name.json" \
      --quiet 2>"$name.err" >/dev/null || code=$?
    secs=$(python3 -c "import sys; print('%.1f' % (float(sys.argv[2]) - float(sys.argv[1])))" "$start" "$(date +%s.%N)")
    solid_pairs=-
    [[ -f $name.stl ]] && solid_pairs=$(pairs "$name.stl")
    reason=$(grep -m1 '^Error' "$name.err" | cut -c1-200 | tr '\t' ' ')
    columns=
    if [[ -n $baseline ]]; then
      old=$out/baseline/${mesh%.*}.${goal%% *}
      old_code=0
      timeout "$limit" "$baseline" optimize "$shared/$mesh" --goal $goal --outer "$@" -o "$old.stl" --report "$old.json" \
        --quiet 2>"$old.err" >/dev/null || old_code=$?
      old_pairs=-
      [[ -f $old.stl ]] && old_pairs=$(pairs "$old.stl")
      columns=$(printf '\t%s\t%s' "$old_code" "$old_pairs")
    fi
    printf '%s\t%s\t%s\t%s\t%s\t%s\t%s%s\n' "$mesh" "${goal%% *}" "$code" "$input_pairs" "$solid_pairs" "$secs" "$reason" "$columns"
  done
done
