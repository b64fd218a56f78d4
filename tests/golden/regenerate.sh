#!/usr/bin/env bash
# Rewrites the golden files from a build of the binary (default build/offsetopt): for every line
# of cases.txt, NAME.json and NAME.ply.sha256 (the digest of the printable solid), and BUILD.txt (`offsetopt --version`: the build they are
# exact for). Run it after a change that is meant to change results, and commit what it writes
# together with that change; the golden test (tests/golden/test_golden.cpp) says which case
# differs and where.
#   tests/golden/regenerate.sh [BINARY]
set -euo pipefail
golden=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$golden/../.." && pwd)
binary=$(realpath "${1:-$root/build/offsetopt}")
cd "$root"
while IFS='|' read -r name expected mesh options; do
  [[ -z $name || $name == \#* ]] && continue
  status=0
  # Outputs are written beside this script under their bare names, so the report names them so.
  (cd "$golden" && "$binary" optimize "../../meshes/$mesh" $options --quiet --no-timings \
    -o "$name.ply" --report "$name.json") || status=$?
  if [[ $status != "$expected" ]]; then
    echo "regenerate: $name exited $status, cases.txt expects $expected" >&2
    exit 1
  fi
  (cd "$golden" && sha256sum "$name.ply" >"$name.ply.sha256" && rm "$name.ply")
  echo "$name: exit $status"
done <"$golden/cases.txt"
"$binary" --version >"$golden/BUILD.txt"
# The quick-start picture of the demo bottle (tests/preview compares it byte for byte).
"$binary" optimize meshes/bottle.obj --goal stand --quiet --no-timings -o "$(mktemp -d)/bottle.ply" \
  --preview "$root/meshes/bottle-stand-preview.svg"
