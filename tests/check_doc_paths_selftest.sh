#!/bin/sh
# The documentation path check (scripts/check_doc_paths.py) on made-up trees: it must pass pages
# whose paths and links exist (and skip ../shared), and fail, naming page and line, on a missing
# path in a code span, in a fenced block or in a link, a link to a missing heading, and on an
# escape that has gone stale.
#   tests/check_doc_paths_selftest.sh REPOSITORY_ROOT
set -u
script=$1/scripts/check_doc_paths.py
tree=$(mktemp -d)
trap 'rm -rf "$tree"' EXIT
mkdir -p "$tree/src/mesh" "$tree/docs" "$tree/tests/golden"
: >"$tree/src/mesh/mesh.h"
: >"$tree/src/mesh/mesh.cpp"
: >"$tree/tests/golden/case.json"

# A page whose paths all exist: a code span, a glob, a line number, a placeholder, a fenced block,
# a link, ../shared (skipped) and an escaped output name.
cat >"$tree/README.md" <<'EOF'
# Demo

`src/mesh/mesh.h:12`, `src/mesh/mesh.*` and `tests/<module>`; the real meshes are in
`../shared/meshes/horse.ply`. See [the page](docs/page.md).

```sh
./src/mesh/mesh.cpp --json -
build/offsetopt optimize x --report tests/golden/new.json
```
<!-- check_doc_paths: created tests/golden/new.json -->
EOF
printf '# Page\n\nBack to the [README](../README.md#demo), and `docs/page.md`.\n' >"$tree/docs/page.md"
python3 "$script" "$tree" >/dev/null 2>&1 || { echo "selftest: pages whose paths exist were refused: $(python3 "$script" "$tree" 2>&1)" >&2; exit 1; }

fails() {  # $1: what the page holds, $2: the report expected
  out=$(python3 "$script" "$tree" 2>&1) && { echo "selftest: passed with $1" >&2; exit 1; }
  echo "$out" | grep -qF "$2" || { echo "selftest: $1: wrong report: $out" >&2; exit 1; }
}

cp "$tree/docs/page.md" "$tree/page.bak"
printf '\nThe loader is `src/mesh/load_mesh.h`.\n' >>"$tree/docs/page.md"
fails "a missing path in a code span" 'docs/page.md:5: `src/mesh/load_mesh.h` does not exist'

cp "$tree/page.bak" "$tree/docs/page.md"
printf '\n```\nbuild/offsetopt preview tests/golden/case.ply\n```\n' >>"$tree/docs/page.md"
fails "a missing path in a fenced block" 'docs/page.md:6: `tests/golden/case.ply` does not exist'

cp "$tree/page.bak" "$tree/docs/page.md"
printf '\nSee [the picture](../meshes/none.svg).\n' >>"$tree/docs/page.md"
fails "a broken link" 'docs/page.md:5: link to ../meshes/none.svg does not exist'

cp "$tree/page.bak" "$tree/docs/page.md"
printf '\nSee [the start](../README.md#nowhere).\n' >>"$tree/docs/page.md"
fails "a link to a heading that is not there" 'docs/page.md:5: link to ../README.md#nowhere: no such heading in ../README.md'

cp "$tree/page.bak" "$tree/docs/page.md"
printf '\nA span over two lines: `build/offsetopt preview\ntests/golden/case.ply`.\n' >>"$tree/docs/page.md"
fails "a missing path in a span over two lines" '`tests/golden/case.ply` does not exist'

cp "$tree/page.bak" "$tree/docs/page.md"
printf '\n<!-- check_doc_paths: created tests/golden/case.json -->\n' >>"$tree/docs/page.md"
fails "an escape naming a path the page does not mention" 'escape names tests/golden/case.json, which the page does not mention'

printf '\n`tests/golden/case.json`\n' >>"$tree/docs/page.md"
fails "an escape naming a path that exists" 'escape names tests/golden/case.json, which exists'

echo "selftest: the documentation path check passes existing paths and refuses missing ones"
