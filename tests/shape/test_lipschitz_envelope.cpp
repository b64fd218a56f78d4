// lipschitz_envelope (shape/lipschitz_envelope.h) against an independent fixed point: relaxing
// every edge both ways over and over (Bellman-Ford order, no queue) until nothing changes gives
// the minimum over paths of the left-to-right path sums, which the Dijkstra search must match bit
// for bit, ties and all.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>

#include "mesh/primitives.h"
#include "shape/lipschitz_envelope.h"
#include "util/rng.h"

using namespace offsetopt;

namespace {

Eigen::VectorXd relaxed_to_fixed_point(const Mesh& mesh, const Eigen::VectorXd& values, double slope) {
  Eigen::VectorXd out = values;
  for (bool changed = true; changed;) {
    changed = false;
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
      for (int c = 0; c < 3; ++c) {
        const int a = mesh.F(f, c), b = mesh.F(f, (c + 1) % 3);
        const double length = (mesh.V.row(a) - mesh.V.row(b)).norm() * slope;
        if (out(a) + length < out(b)) out(b) = out(a) + length, changed = true;
        if (out(b) + length < out(a)) out(a) = out(b) + length, changed = true;
      }
  }
  return out;
}

}  // namespace

TEST_CASE("lipschitz_envelope: the same bits as relaxing every edge to a fixed point, and never above the values") {
  const Mesh sphere = make_icosphere(1.0, 3);
  Rng rng(20261126);
  for (const double slope : {0.0, 0.3, 1.0, 4.0}) {
    Eigen::VectorXd values(sphere.V.rows());
    // Repeated values as well as spread ones: ties in the queue must not change the result.
    for (Eigen::Index i = 0; i < values.size(); ++i) values(i) = (rng.next_u64() % 4 == 0) ? 0.5 : rng.uniform() * 3.0 - 1.0;
    const Eigen::VectorXd envelope = lipschitz_envelope(sphere, values, slope);
    const Eigen::VectorXd expected = relaxed_to_fixed_point(sphere, values, slope);
    for (Eigen::Index i = 0; i < values.size(); ++i) {
      CHECK(envelope(i) == expected(i));
      CHECK(envelope(i) <= values(i));
    }
  }
}
