#!/usr/bin/env bash
# Builds and runs bench/optim/solver_settings.cpp (the solver's settings on every mesh of a
# folder) against the project's core library (Release build).
# Usage: bench/optim/solver_settings.sh DIR [--goal G] [--outer] [--fill-density R] SETTING...
#   e.g. DIR=$(mktemp -d); tar -xJf ../shared/realposed/meshes.tar.xz -C "$DIR"
#        bench/optim/solver_settings.sh "$DIR" initial_inner_tolerance=1e-3 initial_penalty=100
set -euo pipefail
cd "$(dirname "$0")/../.."
bench/optim/build_bench.sh solver_settings
build/bench/solver_settings "$@"
