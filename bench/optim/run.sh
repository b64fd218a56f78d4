#!/usr/bin/env bash
# Builds and runs the solver benchmark against the project's core library (Release build).
# Usage: bench/optim/run.sh [rows [variables [trace]]]   (default: 100000 36)
set -euo pipefail
cd "$(dirname "$0")/../.."
bench/optim/build_bench.sh bench_optim
build/bench/bench_optim "$@"
