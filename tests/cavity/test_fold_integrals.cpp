// The folds' integrals (cavity/fold_integrals.h) against closed forms: a surface that folds
// nowhere has none; a cube the inner surface turns inside out (winding −1) adds the cube's
// integrals, a region it covers twice (winding 2) takes the overlap's away, both within the
// grid's error; the wall's cut of an inner box that pokes out of the outer one is the slab beyond
// the contour's node level; and the contour that reads the winding numbers computed here is the
// one it makes by itself, bit for bit.
#include <doctest/doctest.h>

#include <cmath>

#include "../mesh_checks.h"

#include "cavity/contour_cavity.h"
#include "cavity/fold_integrals.h"
#include "geometry/aabb.h"
#include "geometry/bvh.h"
#include "mass/volume_integrals.h"
#include "mesh/primitives.h"

using namespace offsetopt;

namespace {

Mesh inside_out(Mesh m) {
  m.F.col(1).swap(m.F.col(2));
  return m;
}

// The exact integrals of the box [lo, hi] (mass/volume_integrals.h order), about the origin.
Vector10d box_integrals(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  return volume_integrals(make_box(lo, hi), Eigen::Vector3d::Zero()).values;
}

ContourCavityOptions options_with_wall(double wall) {
  ContourCavityOptions o;
  o.wall = wall;
  return o;
}

// The grid's error on a region of surface area `area`: each node stands for its cube of side h,
// so at most the layer of half a diagonal, √3/2 h, around the surface is misread.
double volume_bound(double area, double h) { return area * std::sqrt(3.0) / 2.0 * h; }

}  // namespace

TEST_CASE("fold integrals: a sphere inside a sphere folds nowhere") {
  const Mesh outer = make_icosphere(10.0, 4), inner = make_icosphere(7.0, 4);
  const FoldIntegrals f = fold_integrals(outer, inner, options_with_wall(1.0), Eigen::Vector3d::Zero(), 1.0);
  REQUIRE(f.ok);
  CHECK(f.folded_nodes == 0);
  CHECK(f.integrals.isZero(0.0));
  CHECK(f.volume == 0.0);
  CHECK(f.inner.winding.size() == static_cast<std::size_t>(f.inner.grid.node_count()));
}

TEST_CASE("fold integrals: a cube turned inside out adds the cube, a region covered twice takes the overlap away") {
  const Mesh outer = make_box(Eigen::Vector3d(-10, -10, -10), Eigen::Vector3d(10, 10, 10));
  const Eigen::Vector3d lo(-7, -7, -7), hi(1, 7, 7);  // the void
  const Eigen::Vector3d pocket_lo(3, -2, -1), pocket_hi(6, 2, 3);  // apart from the void
  const double wall = 0.5, h = wall / 1.5;

  SUBCASE("winding -1: the pocket's integrals, in the frame asked for") {
    const Mesh inner = test::join(make_box(lo, hi), inside_out(make_box(pocket_lo, pocket_hi)));
    const Eigen::Vector3d origin(1.0, -2.0, 0.5);
    const double scale = 0.1;
    const FoldIntegrals f = fold_integrals(outer, inner, options_with_wall(wall), origin, scale);
    REQUIRE(f.ok);
    const Vector10d exact = box_integrals((pocket_lo - origin) * scale, (pocket_hi - origin) * scale);
    const double area = 2.0 * (3 * 4 + 4 * 4 + 3 * 4);
    CHECK(f.folded_nodes > 0);
    CHECK(std::fabs(f.volume - 48.0) <= volume_bound(area, h));
    CHECK(std::fabs(f.integrals(kIntVolume) - exact(kIntVolume)) <= volume_bound(area, h) * std::pow(scale, 3));
    // The centroid, and the second moments about it, within the grid's error.
    const Eigen::Vector3d centroid = f.integrals.segment<3>(kIntX) / f.integrals(kIntVolume);
    const Eigen::Vector3d exact_centroid = exact.segment<3>(kIntX) / exact(kIntVolume);
    CHECK((centroid - exact_centroid).norm() <= h * scale);
    for (int k = kIntXX; k <= kIntZZ; ++k) CHECK(std::fabs(f.integrals(k) / exact(k) - 1.0) < 0.2);
  }

  SUBCASE("winding 2: minus the overlap") {
    const Eigen::Vector3d second_lo(-3, -3, -3), second_hi(5, 3, 3);  // overlaps the void in [-3, 1] × [-3, 3]²
    const Mesh inner = test::join(make_box(lo, hi), make_box(second_lo, second_hi));
    const FoldIntegrals f = fold_integrals(outer, inner, options_with_wall(wall), Eigen::Vector3d::Zero(), 1.0);
    REQUIRE(f.ok);
    const double overlap = 4.0 * 6.0 * 6.0, area = 2.0 * (4 * 6 + 4 * 6 + 6 * 6);
    CHECK(std::fabs(f.volume + overlap) <= volume_bound(area, h));
    CHECK(std::fabs(f.integrals(kIntX) / f.integrals(kIntVolume) - (-1.0)) <= h);
  }
}

TEST_CASE("wall cut integrals: an inner box through the outer one loses the slab past the node level") {
  const Mesh outer = make_box(Eigen::Vector3d(-10, -10, -10), Eigen::Vector3d(10, 10, 10));
  const TriangleBvh outer_bvh(outer.V, outer.F);
  // 1 beyond x = 10: within the contour's grid, which ends 3.5 cells past the outer box.
  const Mesh inner = make_box(Eigen::Vector3d(-7, -5, -5), Eigen::Vector3d(11, 5, 5));
  const ContourCavityOptions options = options_with_wall(0.5);
  const FoldIntegrals folds = fold_integrals(outer, inner, options, Eigen::Vector3d::Zero(), 1.0);
  REQUIRE(folds.ok);
  CHECK(folds.folded_nodes == 0);
  const double h = folds.inner.grid.spacing;
  const double level = cavity_node_level(options.wall, h, options.margin_cells, bounding_box(outer.V));
  const WallCutIntegrals cut = wall_cut_integrals(outer, outer_bvh, folds, options, Eigen::Vector3d::Zero(), 1.0);
  // The slab x in [10 − level, 11] of the 10 × 10 section; the section's sides keep 5 from the outer faces.
  const double slab = (1.0 + level) * 100.0;
  CHECK(cut.volume < 0.0);
  CHECK(std::fabs(-cut.volume - slab) <= volume_bound(2.0 * 100.0 + 4.0 * 10.0 * (1.0 + level), h));
  CHECK(std::fabs(cut.integrals(kIntX) / cut.integrals(kIntVolume) - (10.0 - level + 11.0) / 2.0) <= h);
  // One thread or four: the same bits.
  ContourCavityOptions one = options;
  one.threads = 1;
  ContourCavityOptions four = options;
  four.threads = 4;
  CHECK(wall_cut_integrals(outer, outer_bvh, folds, one, Eigen::Vector3d::Zero(), 1.0).integrals ==
        wall_cut_integrals(outer, outer_bvh, folds, four, Eigen::Vector3d::Zero(), 1.0).integrals);
}

TEST_CASE("fold integrals: the contour reading their winding numbers is the contour made without them") {
  const Mesh outer = make_icosphere(10.0, 4);
  const TriangleBvh outer_bvh(outer.V, outer.F);
  const Mesh inner = test::join(make_icosphere(6.0, 3), inside_out(make_box(Eigen::Vector3d(-2, -2, 6.5), Eigen::Vector3d(2, 2, 8))));
  const ContourCavityOptions options = options_with_wall(1.0);
  const FoldIntegrals f = fold_integrals(outer, inner, options, Eigen::Vector3d::Zero(), 1.0);
  REQUIRE(f.ok);
  CHECK(f.folded_nodes > 0);
  const ContourCavity alone = contour_cavity(outer, outer_bvh, inner, options);
  const ContourCavity reading = contour_cavity(outer, outer_bvh, inner, options, &f.inner);
  REQUIRE(alone.ok);
  REQUIRE(reading.ok);
  CHECK(alone.cavity.V == reading.cavity.V);
  CHECK(alone.cavity.F == reading.cavity.F);
  // Winding numbers of another grid are not read.
  GridWinding other = f.inner;
  other.grid.spacing *= 1.01;
  std::fill(other.winding.begin(), other.winding.end(), std::int8_t{0});
  const ContourCavity elsewhere = contour_cavity(outer, outer_bvh, inner, options, &other);
  CHECK(elsewhere.cavity.V == alone.cavity.V);
}
