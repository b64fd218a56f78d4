#!/bin/sh
# Skeleton-stage benchmark: builds the library (Release) if needed, compiles bench_skeleton.cpp
# against it with the project's flags, and times meshes of about 10k, 40k, 100k and 160k
# vertices, one process each (peak memory per mesh). Real meshes from ../shared/meshes are added
# when present. Run it once; the machine is shared.
set -e
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${BUILD:-$root/build}
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j2 --target offsetopt_core >/dev/null
exe="$build/bench_skeleton"
g++ -std=c++17 -O3 -DNDEBUG -ffp-contract=off -fno-fast-math -I"$root/src" -isystem /usr/include/eigen3 \
  "$here/bench_skeleton.cpp" "$build/liboffsetopt_core.a" -o "$exe"
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), load: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "seconds = wall clock of laplacian_contraction (ordering, symbolic analysis, all steps); cpu = user time of all threads"
"$exe" sphere 5        # 10242 vertices
"$exe" torus 200 50    # 10000
"$exe" sphere 6        # 40962
"$exe" torus 400 100   # 40000
"$exe" torus 640 160   # 102400
"$exe" sphere 7        # 163842
"$exe" torus 800 200   # 160000
shared="$root/../shared/meshes"
for mesh in camel.off armadillo.off horse.ply Armadillo.ply; do
  if [ -f "$shared/$mesh" ]; then "$exe" file "$shared/$mesh"; fi
done
