#!/usr/bin/env bash
# Every goal on every mesh of ../shared/meshes (skips cleanly when the folder is absent): exit
# code, the written cavity, seconds, and the first line of the reason. The table of real-mesh
# outcomes in docs/real-meshes.md is this script's output. `volume` asks for 30% of the object's
# volume, `float` for fluid density 0.8 (the object must be lighter than the fluid it displaces).
# usage: bench/optimize/real_goals.sh [BINARY] [EXTRA OPTIONS...]
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
binary=${1:-$root/build/offsetopt}
shift || true
shared=$root/../shared/meshes
if [[ ! -d $shared ]]; then
  echo "note: ../shared/meshes is absent; nothing to run"
  exit 0
fi
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
printf 'mesh\tgoal\texit\tcavity\tseconds\treason\n'
for mesh in kitten_lowres.obj rocker_arm.off elephant.off fertility.off camel.off armadillo.off horse.ply \
  Armadillo.ply 20mm-xyz-cube.stl hinge.stl spinit_kitten.obj spinit_dolphin.obj; do
  [[ -f $shared/$mesh ]] || continue
  volume=$("$binary" inspect "$shared/$mesh" --json - 2>/dev/null |
    python3 -c "import json,sys; print(json.load(sys.stdin)['volume'] * 0.3)" 2>/dev/null || echo 1)
  for goal in "stand" "stand-filled --fill-density 0.8" "roly-poly" "spin" "volume --target-volume $volume" \
    "float --fluid-density 0.8"; do
    start=$(date +%s.%N)
    code=0
    timeout 900 "$binary" optimize "$shared/$mesh" --goal $goal "$@" -o "$out/solid.stl" --report "$out/r.json" \
      --quiet 2>"$out/err" >/dev/null || code=$?
    secs=$(python3 -c "import sys; print('%.1f' % (float(sys.argv[2]) - float(sys.argv[1])))" "$start" "$(date +%s.%N)")
    cavity=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['cavity']['written'])" "$out/r.json" 2>/dev/null || echo -)
    reason=$(grep -m1 '^Error' "$out/err" | cut -c1-220 | tr '\t' ' ')
    printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$mesh" "${goal%% *}" "$code" "$cavity" "$secs" "$reason"
    rm -f "$out/r.json"
  done
done
