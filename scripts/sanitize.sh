#!/usr/bin/env bash
# The whole test suite under AddressSanitizer + UndefinedBehaviorSanitizer (g++, -O1, assertions
# and Eigen's index checks on), built in build-asan/. Any sanitizer report fails the test that
# triggered it, and so this script. The CLI tests run the sanitized binary too.
#   scripts/sanitize.sh            build and run the fast tests (label `unit`: the library in
#                                  process). The `cli` and `golden` labels run the binary end to
#                                  end; the normal suite runs them, and under the sanitizers on a
#                                  loaded 2-core machine single runs passed their 300 s caps
#   scripts/sanitize.sh REGEX      only the CTest tests matching REGEX (ctest -R), any label
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/deps.sh
jobs=$(nproc)
cmake -S . -B build-asan -DOFFSETOPT_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" >/dev/null
cmake --build build-asan -j"$jobs"
# halt_on_error: the first report ends the process with a failing exit code; detect_leaks: LSan
# is part of ASan on Linux (leaks fail too). UBSan is built with -fno-sanitize-recover already.
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:abort_on_error=0:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
if (($#)); then
  ctest --test-dir build-asan --output-on-failure -j"$jobs" -R "$1"
else
  ctest --test-dir build-asan --output-on-failure -j"$jobs" -L unit
fi
