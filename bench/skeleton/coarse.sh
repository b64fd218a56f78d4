#!/bin/sh
# The two stages of a large run before the skeleton (issue 22): loading (reading, validation, the
# self-intersection and pinch searches) and the coarse copy (the decimation, then each input
# vertex's closest coarse point), on the bottle at 113k, 338k and 10^6 vertices, one thread, one
# process each. Builds the library (Release) if needed and compiles bench_coarse.cpp against it.
# CALLGRIND=1 runs the 113k bottle under callgrind instead (instruction counts, about 2 minutes).
set -e
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${BUILD:-$root/build}
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j2 --target offsetopt offsetopt_core >/dev/null
exe="$build/bench_coarse"
g++ -std=c++17 -O3 -g -DNDEBUG -ffp-contract=off -fno-fast-math -I"$root/src" -isystem /usr/include/eigen3 \
  "$here/bench_coarse.cpp" "$build/liboffsetopt_core.a" -o "$exe" -lpthread
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "machine: $(nproc) cores, load: $(cut -d' ' -f1-3 /proc/loadavg)"
if [ -n "$CALLGRIND" ]; then
  "$build/offsetopt" generate bottle --detail 5.8 -o "$tmp/b.obj"
  valgrind --tool=callgrind --callgrind-out-file="$tmp/cg.out" "$exe" "$tmp/b.obj" >/dev/null 2>&1
  callgrind_annotate --inclusive=yes "$tmp/cg.out" | grep -E 'load_mesh\(|find_self_intersections|find_pinches|decimate_mesh|coarse_copy\(' | cut -c1-110
  exit 0
fi
for detail in 5.8 10 17.2; do
  "$build/offsetopt" generate bottle --detail "$detail" -o "$tmp/b.obj"
  echo "bottle --detail $detail"
  "$exe" "$tmp/b.obj"
done
