#!/usr/bin/env bash
# The generous cells counted in part (bench/cavity/wall_deep_shares.cpp): the demo sphere at the
# tool's default wall (its largest void keeping the wall holds 101,515.9, by half-space
# intersection of the icosphere's faces moved in by the wall).
# usage: bench/cavity/wall_deep_shares.sh [THREADS=2]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
threads=${1:-2}
[[ -f $root/build/liboffsetopt_core.a ]] || cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$root/build" -j2 --target offsetopt_core >/dev/null
mkdir -p "$root/build/bench"
g++ -O2 -std=c++17 -ffp-contract=off -fno-fast-math -DEIGEN_DONT_PARALLELIZE -I "$root/src" -I /usr/include/eigen3 \
  "$root/bench/cavity/wall_deep_shares.cpp" "$root/build/liboffsetopt_core.a" -o "$root/build/bench/wall_deep_shares" -pthread
echo "machine: $(nproc) cores, load: $(cut -d' ' -f1-3 /proc/loadavg)"
"$root/build/bench/wall_deep_shares" "$root/meshes/sphere.obj" 1.0392304845413265 "$threads"
