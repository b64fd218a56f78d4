#!/usr/bin/env bash
# Builds build/bench/NAME from bench/optim/NAME.cpp against the project's core library (Release
# build), for the scripts beside it (run.sh, solver_settings.sh).
# Usage: bench/optim/build_bench.sh NAME
set -euo pipefail
cd "$(dirname "$0")/../.."
if [ ! -f build/CMakeCache.txt ]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build build -j2 --target offsetopt_core >/dev/null
mkdir -p build/bench
g++ -O2 -std=c++17 -ffp-contract=off -fno-fast-math -Wall -Wextra -Wshadow -DEIGEN_DONT_PARALLELIZE \
  -I src -I /usr/include/eigen3 "bench/optim/$1.cpp" build/liboffsetopt_core.a -pthread \
  -o "build/bench/$1"
