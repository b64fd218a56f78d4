#!/usr/bin/env bash
# The wall at a contoured cavity's faces (bench/cavity/face_wall.cpp), two ways:
#  1. the demo bottle's `--goal stand` as written (outer and cavity files);
#  2. each real mesh of ../shared/meshes hollowed below 60% of its height (a half-space quadric),
#     wall 1% of its height: how far below the wall faces came before their vertices were
#     lifted, and the smallest wall at faces and vertices after.
# usage: bench/cavity/face_wall.sh [BINARY]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
binary=${1:-$root/build/offsetopt}
[[ -f $root/build/liboffsetopt_core.a ]] || cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$root/build" -j2 --target offsetopt_core >/dev/null
mkdir -p "$root/build/bench"
g++ -O2 -std=c++17 -ffp-contract=off -fno-fast-math -DEIGEN_DONT_PARALLELIZE -I "$root/src" -I /usr/include/eigen3 \
  "$root/bench/cavity/face_wall.cpp" "$root/build/liboffsetopt_core.a" -o "$root/build/bench/face_wall"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$binary" optimize "$root/meshes/bottle.obj" --goal stand -o "$out/s.stl" --inner "$out/i.stl" --outer-mesh "$out/o.stl" \
  --report "$out/r.json" --quiet || true
wall=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['after']['requested_wall'])" "$out/r.json")
printf 'bottle --goal stand (written, float32): '
"$root/build/bench/face_wall" "$out/o.stl" "$out/i.stl" "$wall"
shared=$root/../shared/meshes
[[ -d $shared ]] || { echo "note: ../shared/meshes is absent"; exit 0; }
for m in "$shared"/*.{stl,ply,off,obj}; do
  printf '%-22s ' "$(basename "$m")"
  "$root/build/bench/face_wall" --contour "$m" 0.01 0.6 | tr '\n' ' '; echo
done
