#!/usr/bin/env bash
# check's self-intersecting face pairs against CGAL's (../shared/tools/validity, exact predicates)
# on every real mesh at hand: the posed meshes of ../shared/realposed (unpacked into OUTDIR) and
# ../shared/meshes. Prints one row per mesh and a summary line; a row whose counts differ is marked
# DIFFERS. docs/check.md's table is this script's output.
# usage: bench/outer/check_vs_cgal.sh BINARY VALIDITY_BINARY [OUTDIR]
#   MESHES (environment): a list of mesh files instead of the two folders.
# Columns: check's pairs (0 when check found none), its collinear (zero-area) faces, its pinches,
# CGAL's pairs ("not a mesh" when CGAL does not read the file as a polygon mesh, which is what it
# does with a pinch) and the verdict. CGAL lists every zero-area face as a pair (f, f); check
# counts them apart (docs/check.md), so the comparison adds them back.
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
binary=${1:?usage: check_vs_cgal.sh BINARY VALIDITY_BINARY [OUTDIR]}
validity=${2:?usage: check_vs_cgal.sh BINARY VALIDITY_BINARY [OUTDIR]}
out=${3:-${TMPDIR:-/tmp}/offsetopt-check-vs-cgal}
shared=$root/../shared
mkdir -p "$out"
if [[ -z ${MESHES:-} ]]; then
  if [[ -f $shared/realposed/meshes.tar.xz && ! -f $out/cases.tsv ]]; then
    tar -xJf "$shared/realposed/meshes.tar.xz" -C "$out"
  fi
  MESHES="$(ls "$out"/*.ply 2>/dev/null) $(ls "$shared"/meshes/*.{ply,off,obj,stl} 2>/dev/null)"
fi
printf 'mesh\tcheck_pairs\tcheck_collinear\tcheck_pinches\tcgal_pairs\tverdict\n'
rows=0 agree=0 differ=0 unread=0
for mesh in $MESHES; do
  err=$("$binary" check "$mesh" 2>&1 >/dev/null)
  read -r pairs collinear pinches < <(python3 - "$err" <<'EOF'
import re, sys
text = sys.argv[1]
def first(pattern):
    m = re.search(pattern, text)
    return int(m.group(1)) if m else 0
print(first(r'(\d+) self-intersecting face pair'), first(r'(\d+) zero-area faces? with three distinct collinear'),
      first(r'(\d+) pinch'))
EOF
)
  # validity exits 1 for a mesh that is not valid: its count is still the answer (pipefail).
  cgal=$({ "$validity" "$mesh" 2>/dev/null || true; } | python3 -c "
import json, sys
d = json.loads(sys.stdin.read())
print(d['self_intersecting_pairs'] if d.get('manifold') else 'not_a_mesh')" 2>/dev/null || echo '?')
  if [[ $cgal == not_a_mesh ]]; then
    verdict=$([[ $pinches -gt 0 ]] && echo "pinch (CGAL: not a polygon mesh)" || echo "DIFFERS (CGAL: not a polygon mesh)")
    [[ $pinches -gt 0 ]] && unread=$((unread + 1)) || differ=$((differ + 1))
  elif [[ $cgal == "$((pairs + collinear))" ]]; then
    verdict=same; agree=$((agree + 1))
  else
    verdict=DIFFERS; differ=$((differ + 1))
  fi
  rows=$((rows + 1))
  printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$(basename "$mesh")" "$pairs" "$collinear" "$pinches" "${cgal/not_a_mesh/not a mesh}" "$verdict"
done
echo "check vs CGAL: $rows meshes; same pair count $agree; pinched (CGAL reads no polygon mesh) $unread; differ $differ"
