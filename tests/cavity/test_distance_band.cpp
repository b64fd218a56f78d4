// distance_band (cavity/distance_band.h) by points and by faces against the rule it promises, each
// point's count of thresholds t with no face nearer than t (face_within(bvh, p, t, true)), asked of
// every point: on an icosphere (curved, points at every distance) and on a box whose grid puts
// points exactly a threshold away from its faces (the ties the rule decides), with masks, one and
// two threads, and the automatic choice.
#include <doctest/doctest.h>

#include <cstdint>
#include <vector>

#include "cavity/distance_band.h"
#include "geometry/bvh.h"
#include "geometry/closest_point.h"
#include "geometry/node_grid.h"
#include "mesh/primitives.h"

using namespace offsetopt;

namespace {

std::vector<std::int8_t> by_rule(const NodeGrid& g, const std::vector<std::int8_t>& mask, const TriangleBvh& bvh,
                                 const std::vector<double>& thresholds) {
  std::vector<std::int8_t> band(static_cast<std::size_t>(g.node_count()), 0);
  for (std::int64_t k = 0; k < g.nz; ++k)
    for (std::int64_t j = 0; j < g.ny; ++j)
      for (std::int64_t i = 0; i < g.nx; ++i) {
        const std::size_t v = static_cast<std::size_t>(g.index(i, j, k));
        if (!mask[v]) continue;
        std::int8_t reached = 0;
        while (reached < static_cast<std::int8_t>(thresholds.size()) &&
               !face_within(bvh, g.position(i, j, k), thresholds[static_cast<std::size_t>(reached)], true))
          ++reached;
        band[v] = reached;
      }
  return band;
}

void check_every_method(const Mesh& mesh, const NodeGrid& g, const std::vector<double>& thresholds) {
  const TriangleBvh bvh(mesh.V, mesh.F);
  std::vector<std::int8_t> all(static_cast<std::size_t>(g.node_count()), 1), some = all;
  for (std::size_t v = 0; v < some.size(); ++v) some[v] = (v * 7) % 3 != 0;
  for (const std::vector<std::int8_t>* mask : {&all, &some}) {
    const std::vector<std::int8_t> expected = by_rule(g, *mask, bvh, thresholds);
    int reached_some = 0, reached_none = 0;
    for (std::size_t v = 0; v < expected.size(); ++v) {
      if (!(*mask)[v]) continue;
      reached_some += expected[v] > 0 && expected[v] < static_cast<std::int8_t>(thresholds.size());
      reached_none += expected[v] == 0;
    }
    REQUIRE(reached_some > 100);  // the thresholds cut through the grid
    REQUIRE(reached_none > 100);
    for (const BandMethod method : {BandMethod::by_points, BandMethod::by_faces, BandMethod::automatic})
      for (const int threads : {1, 2}) {
        CAPTURE(static_cast<int>(method));
        CAPTURE(threads);
        std::int64_t queries = 0;
        CHECK(distance_band(g, *mask, bvh, thresholds, threads, queries, method) == expected);
      }
  }
}

}  // namespace

TEST_CASE("distance_band by points and by faces: the thresholds every point reaches, on a sphere") {
  const Mesh sphere = make_icosphere(5.0, 3);
  NodeGrid g;
  g.origin = Eigen::Vector3d(-6.1, -6.05, -6.2);
  g.spacing = 0.37;
  g.nx = g.ny = g.nz = 34;
  check_every_method(sphere, g, {0.3, 1.0, 1.9});
}

TEST_CASE("distance_band by points and by faces: points exactly a threshold from a box's faces") {
  // The box [0, 8]^3 on a grid of step 0.5 from -1: nodes lie exactly 1.0 and 2.0 from the face
  // planes (and from edges and corners along the axes), where d >= t holds with equality.
  const Mesh box = make_box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(8.0));
  NodeGrid g;
  g.origin = Eigen::Vector3d::Constant(-1.0);
  g.spacing = 0.5;
  g.nx = g.ny = g.nz = 21;
  check_every_method(box, g, {1.0, 2.0});
}
