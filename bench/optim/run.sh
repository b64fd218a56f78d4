#!/usr/bin/env bash
# Builds and runs the solver benchmark against the project's core library (Release build).
# Usage: bench/optim/run.sh [rows [variables [trace]]]   (default: 100000 36)
set -euo pipefail
cd "$(dirname "$0")/../.."
if [ ! -f build/liboffsetopt_core.a ]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build build -j2 --target offsetopt_core >/dev/null
mkdir -p build/bench
g++ -O2 -std=c++17 -ffp-contract=off -fno-fast-math -Wall -Wextra -Wshadow -DEIGEN_DONT_PARALLELIZE \
  -I src -I /usr/include/eigen3 bench/optim/bench_optim.cpp build/liboffsetopt_core.a \
  -o build/bench/bench_optim
build/bench/bench_optim "$@"
