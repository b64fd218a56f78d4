// Times the two stages of a large run that come before the skeleton (issue 22): loading an input
// (reading, validation, the self-intersection and pinch searches of meshio/load_input.h) and the
// coarse copy (the decimation of skeleton/decimate_mesh.h, then every input vertex's closest coarse
// point). Prints one line per part: wall and CPU seconds. One thread, so callgrind counts the same.
//
//   bench_coarse PATH [TARGET]     TARGET coarse vertices, 30000 unless given
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "geometry/mesh_defects.h"
#include "meshio/load_mesh.h"
#include "skeleton/coarse_copy.h"

using namespace offsetopt;

namespace {

double cpu_seconds() {
  struct rusage usage {};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

struct Clock {
  std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
  double cpu = cpu_seconds();
  void lap(const char* what) {
    const auto now = std::chrono::steady_clock::now();
    const double cpu_now = cpu_seconds();
    std::printf("%-22s wall %7.2f s  cpu %7.2f s\n", what, std::chrono::duration<double>(now - wall).count(), cpu_now - cpu);
    wall = now;
    cpu = cpu_now;
  }
};

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_coarse PATH [TARGET]\n");
    return 2;
  }
  const int target = argc > 2 ? std::atoi(argv[2]) : 30000;
  Clock clock;
  LoadOptions load_options;
  load_options.single_component = true;
  const LoadedMesh loaded = load_mesh(argv[1], load_options);
  clock.lap("load_mesh");
  const SelfIntersectionReport crossings = find_self_intersections(loaded.mesh);
  clock.lap("self-intersections");
  const PinchReport pinches = find_pinches(loaded.mesh);
  clock.lap("pinches");
  const DecimatedMesh decimated = decimate_mesh(loaded.mesh.V, loaded.mesh.F, target);
  clock.lap("decimate_mesh");
  const CoarseCopy copy = coarse_copy(loaded.mesh.V, loaded.mesh.F, target, 1);
  clock.lap("coarse_copy (again)");
  std::printf("%ld vertices, %zu crossing pairs, %zu pinches, coarse %ld vertices %ld faces\n",
              static_cast<long>(loaded.mesh.V.rows()), static_cast<std::size_t>(crossings.pairs),
              static_cast<std::size_t>(pinches.pairs), static_cast<long>(decimated.mesh.V.rows()),
              static_cast<long>(copy.decimated.mesh.F.rows()));
  return 0;
}
