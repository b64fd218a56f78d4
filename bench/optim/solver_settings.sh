#!/usr/bin/env bash
# Builds and runs bench/optim/solver_settings.cpp (the solver's settings on every mesh of a
# folder) against the project's core library (Release build).
# Usage: bench/optim/solver_settings.sh DIR [--goal G] [--outer] [--fill-density R] SETTING...
#   e.g. DIR=$(mktemp -d); tar -xJf ../shared/realposed/meshes.tar.xz -C "$DIR"
#        bench/optim/solver_settings.sh "$DIR" initial_inner_tolerance=1e-3 initial_penalty=100
set -euo pipefail
cd "$(dirname "$0")/../.."
if [ ! -f build/CMakeCache.txt ]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build build -j2 --target offsetopt_core >/dev/null
mkdir -p build/bench
g++ -O2 -std=c++17 -ffp-contract=off -fno-fast-math -Wall -Wextra -Wshadow -DEIGEN_DONT_PARALLELIZE \
  -I src -I /usr/include/eigen3 bench/optim/solver_settings.cpp build/liboffsetopt_core.a -pthread \
  -o build/bench/solver_settings
build/bench/solver_settings "$@"
