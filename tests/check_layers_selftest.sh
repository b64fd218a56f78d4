#!/bin/sh
# The layer check (scripts/check_layers.py) on made-up trees: it must pass a tree whose includes
# point down, and fail, naming file and line, on one that includes upwards or has a folder the
# Layers: line does not place.
#   tests/check_layers_selftest.sh REPOSITORY_ROOT
set -u
script=$1/scripts/check_layers.py
tree=$(mktemp -d)
trap 'rm -rf "$tree"' EXIT
mkdir -p "$tree/src/low" "$tree/src/high"
printf 'Layers: low → high\n' >"$tree/README.md"
printf '#include "low/a.h"\n' >"$tree/src/high/b.h"
printf '#pragma once\n' >"$tree/src/low/a.h"
python3 "$script" "$tree" >/dev/null 2>&1 || { echo "selftest: a downward include was refused" >&2; exit 1; }
printf '#pragma once\n\n#include "high/b.h"\n' >"$tree/src/low/a.h"
out=$(python3 "$script" "$tree" 2>&1) && { echo "selftest: an upward include passed" >&2; exit 1; }
echo "$out" | grep -q 'src/low/a.h:3: low includes high/' || { echo "selftest: wrong report: $out" >&2; exit 1; }
printf '#pragma once\n' >"$tree/src/low/a.h"
mkdir -p "$tree/src/stray"
out=$(python3 "$script" "$tree" 2>&1) && { echo "selftest: an unplaced folder passed" >&2; exit 1; }
echo "$out" | grep -q 'src/stray: not on' || { echo "selftest: wrong report: $out" >&2; exit 1; }
echo "selftest: the layer check passes down, refuses up and unplaced folders"
