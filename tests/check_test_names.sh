#!/bin/sh
# doctest_discover_tests hands test names to CMake, which splits them at ';' (its list
# separator): a TEST_CASE whose name holds one becomes tests that run nothing and still pass.
# This check fails on any such name under the folder given (default: this script's folder).
#   tests/check_test_names.sh [FOLDER]
folder=${1:-$(dirname "$0")}
if grep -rnP --include='test_*.cpp' 'TEST_CASE\("[^"]*\x3b' "$folder"; then
  echo "check_test_names: the TEST_CASE names above contain ';', which CTest discovery splits; use ',' or ':'" >&2
  exit 1
fi
