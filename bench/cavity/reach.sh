#!/usr/bin/env bash
# Builds the reachability benchmark against the core library (Release) and runs it:
#   bench/cavity/reach.sh MESH GOAL [options]      one run
#   bench/cavity/reach.sh --real                   the cases compared with ../shared/tools/reach/carve.py
#   bench/cavity/reach.sh --bottle                 the 100k-vertex demo bottle, stand, read as optimize reads it
#                                                  (--mid: the mid cells, no node pass; the speed figure)
set -euo pipefail
cd "$(dirname "$0")/../.."
if [ ! -f build/liboffsetopt_core.a ]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build build -j2 --target offsetopt_core offsetopt >/dev/null
mkdir -p build/bench
g++ -O2 -std=c++17 -ffp-contract=off -fno-fast-math -Wall -Wextra -DEIGEN_DONT_PARALLELIZE -pthread \
  -I src -I /usr/include/eigen3 bench/cavity/bench_reachability.cpp build/liboffsetopt_core.a \
  -o build/bench/bench_reachability
bin=build/bench/bench_reachability
shared=../shared/meshes
case "${1:-}" in
  --real)
    [[ -d $shared ]] || { echo "note: $shared is absent"; exit 0; }
    for m in 20mm-xyz-cube.stl hinge.stl Armadillo.ply; do $bin $shared/$m float --fluid-density 0.8; done
    $bin $shared/camel.off stand
    $bin $shared/horse.ply stand
    $bin $shared/horse.ply stand --outer
    ;;
  --bottle)
    b=$(mktemp -d)/bottle.obj
    build/offsetopt generate bottle --detail 5.8 -o "$b" >/dev/null
    $bin "$b" stand --mid
    $bin "$b" stand --mid --threads 1
    build/offsetopt generate bottle -o "$b" >/dev/null
    $bin "$b" stand --mid
    ;;
  *) $bin "$@" ;;
esac
