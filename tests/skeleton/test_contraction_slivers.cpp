// Laplacian contraction on a CAD-style box (zero-area slivers with distinct corners, needles, a
// cap): with intrinsic mollification of L_t every step stays finite and the volume shrinks, and
// with mollification off the run is the same only where no triangle needs it (first step of a
// clean mesh).
#include <doctest/doctest.h>

#include "../meshio/sliver_box.h"
#include "mesh/primitives.h"
#include "skeleton/laplacian_contraction.h"

using namespace offsetopt;

TEST_CASE("a box with slivers, needles and a cap contracts with finite positions and shrinking volume") {
  const Mesh box = sliver_test::sliver_box();
  ContractionOptions options;
  options.stop_volume_ratio = 0.0;
  options.max_steps = 4;
  const ContractionResult r = laplacian_contraction(box.V, box.F, options);
  CHECK(r.status == ContractionStatus::step_cap);
  REQUIRE(r.steps == 4);
  CHECK(r.V.allFinite());
  for (std::size_t k = 1; k < r.history.size(); ++k) CHECK(r.history[k].volume_ratio < r.history[k - 1].volume_ratio);
  CHECK(r.volume_ratio < 0.5);
}

TEST_CASE("mollification does not change a contraction whose triangles never need it (one step of an icosphere)") {
  const Mesh sphere = make_icosphere(1.0, 2);
  ContractionOptions on, off;
  on.max_steps = off.max_steps = 1;
  off.mollify_margin = 0.0;
  const ContractionResult a = laplacian_contraction(sphere.V, sphere.F, on), b = laplacian_contraction(sphere.V, sphere.F, off);
  CHECK((a.V - b.V).cwiseAbs().maxCoeff() == 0.0);
}
