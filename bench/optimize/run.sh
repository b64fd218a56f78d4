#!/usr/bin/env bash
# Per-stage seconds and peak memory of `offsetopt optimize` for each goal on the demo meshes and,
# when ../shared/meshes is present, on real meshes up to ~100k vertices (a figure, not a test).
# usage: bench/optimize/run.sh [BINARY]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
binary=${1:-$root/build/offsetopt}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

cases=(
  "bottle.obj|--goal stand"
  "bottle.obj|--goal stand-filled --fill-density 0.8 --outer"
  "top.obj|--goal spin"
  "rolypoly.obj|--goal roly-poly"
  "buoy.obj|--goal float --fluid-density 0.806"
  "sphere.obj|--goal volume --target-volume 20000"
)
shared=$root/../shared/meshes
if [[ -d $shared ]]; then
  for m in armadillo.off horse.ply Armadillo.ply; do
    [[ -f $shared/$m ]] && cases+=("$shared/$m|--goal stand")
  done
else
  echo "note: ../shared/meshes is absent; demo meshes only"
fi

printf '%-16s %-46s %6s %7s %7s %7s %7s %7s %8s %5s\n' mesh options verts skel basis solve verify total peakMB exit
for c in "${cases[@]}"; do
  mesh=${c%%|*}; opts=${c#*|}
  [[ $mesh == /* ]] || mesh=$root/meshes/$mesh
  set +e
  /usr/bin/time -f '%M' -o "$out/mem" "$binary" optimize "$mesh" $opts -o "$out/solid.obj" --report "$out/r.json" --quiet 2>/dev/null
  code=$?
  set -e
  /usr/bin/python3 - "$out/r.json" "$out/mem" "$(basename "$mesh")" "$opts" "$code" <<'PY'
import json, sys
r = json.load(open(sys.argv[1])); t = r['timings']; mem = int(open(sys.argv[2]).read().split()[-1]) / 1024
print(f"{sys.argv[3]:16} {sys.argv[4]:46} {r['vertices']:6d} {t['skeleton']:7.3f} {t['basis']:7.3f} {t['solve']:7.3f} "
      f"{t['verify']:7.3f} {t['total'] + t['load'] + t['write']:7.3f} {mem:8.1f} {sys.argv[5]:>5}")
PY
done
