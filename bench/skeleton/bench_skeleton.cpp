// Times the skeleton stage (laplacian_contraction) and the offset field on one mesh and prints
// one line: vertices, steps, status, volume ratio, ordering, predicted factor size, wall and CPU
// seconds, peak resident memory. One mesh per process so the peak memory is that mesh's.
//
//   bench_skeleton sphere S        icosphere with S subdivisions, radially deformed (lumps)
//   bench_skeleton torus M N       torus with M x N vertices, tube radius varying around it
//   bench_skeleton file PATH       any mesh load_mesh reads
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "geometry/bvh.h"
#include "meshio/load_mesh.h"
#include "mesh/primitives.h"
#include "shape/offset_field.h"
#include "skeleton/laplacian_contraction.h"
#include "util/det_math.h"

using namespace offsetopt;

namespace {

double cpu_seconds() {
  struct rusage usage {};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec) + 1e-6 * static_cast<double>(usage.ru_utime.tv_usec);
}

double peak_megabytes() {
  struct rusage usage {};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

Mesh lumpy_sphere(int subdivisions) {
  Mesh m = make_icosphere(1.0, subdivisions);
  for (Eigen::Index i = 0; i < m.V.rows(); ++i) {
    const double x = m.V(i, 0), y = m.V(i, 1), z = m.V(i, 2);
    m.V.row(i) *= 1.0 + 0.2 * det_sin(3.0 * x) * det_cos(2.0 * y) + 0.3 * z * z;
  }
  return m;
}

Mesh varying_torus(int major, int minor) {
  Mesh m = make_torus(1.0, 0.3, major, minor);
  for (Eigen::Index i = 0; i < m.V.rows(); ++i) {
    const double angle = det_atan2(m.V(i, 1), m.V(i, 0));
    const double scale = 1.0 + 0.4 * det_sin(2.0 * angle);
    const double r = std::hypot(m.V(i, 0), m.V(i, 1));
    const double ring = (r - 1.0) * scale + 1.0;
    m.V(i, 0) *= ring / r;
    m.V(i, 1) *= ring / r;
    m.V(i, 2) *= scale;
  }
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: bench_skeleton sphere S | torus M N | file PATH\n");
    return 2;
  }
  const std::string kind = argv[1];
  Mesh mesh;
  std::string label;
  if (kind == "sphere") {
    mesh = lumpy_sphere(std::atoi(argv[2]));
    label = std::string("lumpy sphere s") + argv[2];
  } else if (kind == "torus" && argc >= 4) {
    mesh = varying_torus(std::atoi(argv[2]), std::atoi(argv[3]));
    label = std::string("torus ") + argv[2] + "x" + argv[3];
  } else if (kind == "file") {
    mesh = load_mesh(argv[2]).mesh;
    label = argv[2];
    const std::size_t slash = label.find_last_of('/');
    if (slash != std::string::npos) label = label.substr(slash + 1);
  } else {
    std::fprintf(stderr, "unknown mesh kind '%s'\n", kind.c_str());
    return 2;
  }
  const double cpu0 = cpu_seconds();
  const auto wall0 = std::chrono::steady_clock::now();
  const ContractionResult contraction = laplacian_contraction(mesh.V, mesh.F);
  const double wall_skeleton = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  const double cpu_skeleton = cpu_seconds() - cpu0;
  const auto wall1 = std::chrono::steady_clock::now();
  const double cpu1 = cpu_seconds();
  const TriangleBvh bvh(mesh.V, mesh.F);
  OffsetFieldOptions field_options;
  field_options.wall = 0.01 * bvh.diagonal();
  const OffsetField field = offset_field(mesh, contraction.V, bvh, field_options);
  const double wall_field = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall1).count();
  const double cpu_field = cpu_seconds() - cpu1;
  std::printf("%-22s %8ld vertices  %d steps %-20s vol %.3g  %-17s nnz(L) %.3gM flops %.3g  skeleton %.2f s (cpu %.2f)  field %.2f s (cpu %.2f, %d along -n)  peak %.0f MB\n",
              label.c_str(), static_cast<long>(mesh.V.rows()), contraction.steps, to_string(contraction.status),
              contraction.volume_ratio, contraction.ordering.c_str(), contraction.predicted_factor_nonzeros / 1e6, contraction.predicted_factor_flops, wall_skeleton,
              cpu_skeleton, wall_field, cpu_field, field.fallback_count, peak_megabytes());
  return 0;
}
