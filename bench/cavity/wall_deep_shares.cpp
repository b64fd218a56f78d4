// The generous cells counted in part (cavity/wall_deep_shares.h) on one mesh: for each number of
// halvings, the volume the cells may hold a wall deep, the shell cells and the seconds (a figure,
// not a test). Whole cells are the first line.
//   wall_deep_shares MESH WALL [THREADS=2]
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "cavity/carvable_cells.h"
#include "cavity/wall_deep_shares.h"
#include "geometry/bvh.h"
#include "meshio/load_mesh.h"

using namespace offsetopt;

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: wall_deep_shares MESH WALL [THREADS]\n");
    return 2;
  }
  const Mesh mesh = load_mesh(argv[1]).mesh;
  const double wall = std::strtod(argv[2], nullptr);
  const int threads = argc > 3 ? std::atoi(argv[3]) : 2;
  const TriangleBvh bvh(mesh.V, mesh.F);
  CarvableCellsOptions co;
  co.wall = wall;
  co.threads = threads;
  const CarvableCells cells = carvable_cells(mesh, bvh, co);
  if (!cells.ok) {
    std::fprintf(stderr, "Error: %s\n", cells.message.c_str());
    return 2;
  }
  const double v = cells.cell_volume();
  std::printf("%s wall %g: %zu generous cells of side %g, whole %.1f\n", argv[1], wall, cells.outer.size(), cells.grid.spacing,
              v * static_cast<double>(cells.outer.size()));
  for (int levels = 1; levels <= 5; ++levels) {
    const auto start = std::chrono::steady_clock::now();
    const WallDeepShares s = wall_deep_shares(cells, bvh, wall, levels, threads);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    double held = 0.0;
    for (double share : s.share) held += v * share;
    std::printf("  levels %d: at most %.1f, %lld shell cells, %lld queries, %.3f s\n", levels, held,
                static_cast<long long>(s.shell_cells), static_cast<long long>(s.queries), seconds);
  }
  return 0;
}
