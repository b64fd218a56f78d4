// The wall at a cavity's faces, not only its vertices (a figure, not a test).
//   face_wall OUTER INNER WALL            the written files (e.g. optimize's -o OUTER --inner INNER)
//   face_wall --contour MESH W F          contours MESH's interior below F of its height (a
//                                          half-space quadric), wall W of its height, and
//                                          measures what it wrote
// Each face of the cavity is sampled at the 45 points of a barycentric grid (8 steps per edge),
// every sample measured by an exact closest-point query on the outer surface: independent of the
// triangle distances the contour uses. Faces whose vertices are further than wall + longest edge
// cannot come below the wall (1-Lipschitz) and are not sampled.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "cavity/contour_cavity.h"
#include "geometry/bvh.h"
#include "geometry/closest_point.h"
#include "meshio/load_mesh.h"
#include "meshio/read_raw_mesh.h"

using namespace offsetopt;

namespace {

Mesh read(const std::string& path) {
  RawMesh raw = read_raw_mesh(path);
  Mesh m;
  m.V = raw.V;
  m.F = raw.F;
  return m;
}

void measure(const Mesh& outer, const Mesh& inner, double wall) {
  const TriangleBvh bvh(outer.V, outer.F);
  double vertex_min = INFINITY, face_min = INFINITY;
  long faces_below = 0, sampled = 0;
  const int n = 8;
  for (Eigen::Index f = 0; f < inner.F.rows(); ++f) {
    const Eigen::Vector3d a = inner.V.row(inner.F(f, 0)).transpose(), b = inner.V.row(inner.F(f, 1)).transpose(),
                          c = inner.V.row(inner.F(f, 2)).transpose();
    const double da = closest_point(bvh, a).distance, db = closest_point(bvh, b).distance, dc = closest_point(bvh, c).distance;
    const double least = std::min({da, db, dc});
    vertex_min = std::min(vertex_min, least);
    const double longest = std::max({(a - b).norm(), (b - c).norm(), (c - a).norm()});
    if (least > wall + longest) continue;
    ++sampled;
    double m = least;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        const Eigen::Vector3d p = a + (double(i) / n) * (b - a) + (double(j) / n) * (c - a);
        m = std::min(m, closest_point(bvh, p, m).found ? closest_point(bvh, p).distance : m);
      }
    face_min = std::min(face_min, m);
    if (m < wall) ++faces_below;
  }
  std::printf("faces %ld sampled %ld | smallest wall/request: vertices %.6f, faces %.6f | faces below the wall %ld\n",
              static_cast<long>(inner.F.rows()), sampled, vertex_min / wall, face_min / wall, faces_below);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 5 && std::string(argv[1]) == "--contour") {
    const Mesh outer = load_mesh(argv[2]).mesh;
    const double lo = outer.V.col(2).minCoeff(), hi = outer.V.col(2).maxCoeff();
    const double wall = std::atof(argv[3]) * (hi - lo), fraction = std::atof(argv[4]);
    const TriangleBvh bvh(outer.V, outer.F);
    Vector10d q = Vector10d::Zero();
    q(0) = -(lo + fraction * (hi - lo));
    q(3) = 1.0;
    ContourCavityOptions options;
    options.wall = wall;
    const ContourCavity c = contour_cavity(outer, bvh, q, options);
    if (!c.ok) {
      std::printf("not contoured: %s\n", c.message.c_str());
      return 1;
    }
    std::printf("on the wall %d vertices; before lifting: %d faces below, deepest %.6f of the wall; demotions %d, "
                "faces left below %d\n",
                c.vertices_moved_for_wall, c.faces_lifted, c.largest_face_deficit / wall, c.demotions, c.faces_below_wall);
    measure(outer, c.cavity, wall);
    return 0;
  }
  if (argc != 4) {
    std::fprintf(stderr, "usage: face_wall OUTER INNER WALL | face_wall --contour MESH WALL_OF_HEIGHT FRACTION\n");
    return 2;
  }
  measure(read(argv[1]), read(argv[2]), std::atof(argv[3]));
  return 0;
}
