// The contoured cavity (cavity/contour_cavity.h) against geometric answers: a sphere inside a
// sphere gives one closed cavity whose volume lies between the balls shrunk and grown by the grid's
// error bound, and whose smallest wall (measured exactly, vertex by vertex) is at least the one
// requested; an inner offset surface that folds through itself and crosses the outer surface
// still gives a closed, embedded cavity that keeps the wall; a part left solid (thinner than two walls) gets
// no cavity at all.
#include <doctest/doctest.h>

#include <cmath>
#include <array>
#include <map>
#include <vector>

#include "../mesh_checks.h"
#include "../mass/geometry_checks.h"
#include "geometry/bvh.h"
#include "geometry/closest_point.h"
#include "geometry/intersecting_faces.h"
#include "mass/volume_integrals.h"
#include "mesh/primitives.h"
#include "cavity/contour_cavity.h"

using namespace offsetopt;
using offsetopt::test::closed_and_oriented;

namespace {

double smallest_wall(const TriangleBvh& outer, const Mesh& cavity) {
  double smallest = std::numeric_limits<double>::infinity();
  for (Eigen::Index v = 0; v < cavity.V.rows(); ++v)
    smallest = std::min(smallest, closest_point(outer, cavity.V.row(v).transpose()).distance);
  return smallest;
}

// Every check that makes a cavity printable, on the mesh alone.
void check_printable(const Mesh& outer, const TriangleBvh& outer_bvh, const ContourCavity& c, double wall) {
  REQUIRE(c.ok);
  CHECK(closed_and_oriented(c.cavity));
  const TriangleBvh cavity_bvh(c.cavity.V, c.cavity.F);
  CHECK(self_intersections(cavity_bvh, 10).pairs.empty());
  CHECK(intersecting_faces(cavity_bvh, outer_bvh, 10).pairs.empty());
  CHECK(smallest_wall(outer_bvh, c.cavity) >= wall);
  // Every cavity vertex is inside the outer surface.
  for (Eigen::Index v = 0; v < c.cavity.V.rows(); v += 97)
    CHECK(test::winding_number(outer, c.cavity.V.row(v).transpose()) > 0.5);
}

// An icosphere of radius 7 inside one of radius 10: the cavity is known to lie near radius 7.
struct SphereInSphere {
  double R = 10.0, r = 7.0;
  Mesh outer = make_icosphere(R, 4);
  Mesh inner = make_icosphere(r, 4);
  TriangleBvh outer_bvh{outer.V, outer.F};
};

}  // namespace

TEST_CASE("a sphere inside a sphere: one closed cavity within the grid's error bound, the wall kept") {
  const SphereInSphere spheres;
  const double r = spheres.r, wall = 1.0;
  const Mesh& outer = spheres.outer;
  const Mesh& inner = spheres.inner;
  const TriangleBvh& outer_bvh = spheres.outer_bvh;
  ContourCavityOptions options;
  options.wall = wall;
  for (int threads : {1, 2}) {
    options.threads = threads;
    const ContourCavity c = contour_cavity(outer, outer_bvh, inner, options);
    check_printable(outer, outer_bvh, c, wall);
    CHECK(c.shells == 1);
    // Every cavity vertex lies on a grid edge with a cavity node at one end and a non-cavity node
    // at the other, so within √3 h of the inner surface (the only place φ changes sign here); the
    // inner polyhedron lies between radius r cos(θ) (its face centres) and r.
    const double h = c.grid.spacing;
    const double inscribed = r * inner.V.row(inner.F(0, 0)).normalized().dot(
                                     (inner.V.row(inner.F(0, 0)) + inner.V.row(inner.F(0, 1)) + inner.V.row(inner.F(0, 2))).normalized());
    const double volume = volume_integrals(c.cavity).values(kIntVolume);
    const double pi = 3.141592653589793;
    CHECK(volume >= 4.0 / 3.0 * pi * std::pow(inscribed * 0.999 - std::sqrt(3.0) * h, 3));
    CHECK(volume <= 4.0 / 3.0 * pi * std::pow(r + std::sqrt(3.0) * h, 3));
    // Closer than that in fact: within 2% of the inner polyhedron's volume.
    CHECK(std::fabs(volume / volume_integrals(inner).values(kIntVolume) - 1.0) < 0.02);
  }
}

TEST_CASE("an inner offset surface that folds and crosses the outer one gives a closed embedded cavity") {
  const double R = 10.0, wall = 1.2;
  const Mesh outer = make_icosphere(R, 4);
  Mesh inner = make_icosphere(R, 4);
  // Inward by 3 everywhere, but a cap pushed out through the outer surface (a crossing) and a band
  // pushed in through the centre to the other side (a fold: the surface passes through itself).
  for (Eigen::Index v = 0; v < inner.V.rows(); ++v) {
    const Eigen::Vector3d p = inner.V.row(v).transpose();
    const Eigen::Vector3d n = p.normalized();
    double depth = 3.0;
    if (n.z() > 0.8) depth = -2.0;
    else if (std::fabs(n.x()) < 0.15) depth = 14.0;
    inner.V.row(v) = (p - depth * n).transpose();
  }
  {
    const TriangleBvh inner_bvh(inner.V, inner.F);
    REQUIRE(!self_intersections(inner_bvh, 10).pairs.empty());  // the offset surface does fold
  }
  const TriangleBvh outer_bvh(outer.V, outer.F);
  ContourCavityOptions options;
  options.wall = wall;
  const ContourCavity c = contour_cavity(outer, outer_bvh, inner, options);
  check_printable(outer, outer_bvh, c, wall);
  CHECK(c.cavity.F.rows() > 0);
  // No cavity point comes closer to the outer surface than the wall, so none is above the
  // outer surface's top less the wall.
  CHECK(c.cavity.V.col(2).maxCoeff() <= R - wall + 1e-9);
}

TEST_CASE("a part left solid (thinner than two walls) gets no cavity") {
  const double wall = 1.0;
  const Mesh outer = make_box({0, 0, 0}, {20, 20, 1.8});
  const Mesh inner = make_box({0.2, 0.2, 0.2}, {19.8, 19.8, 1.6});  // an offset surface, 0.2 inside
  const TriangleBvh outer_bvh(outer.V, outer.F);
  ContourCavityOptions options;
  options.wall = wall;
  const ContourCavity c = contour_cavity(outer, outer_bvh, inner, options);
  REQUIRE(c.ok);
  CHECK(c.cavity.F.rows() == 0);
  CHECK(c.shells == 0);
  // The same slab at 2.6 + 2 c h thick has room for a cavity: the test above is not vacuous.
  const Mesh thick = make_box({0, 0, 0}, {20, 20, 4.0});
  const Mesh thick_inner = make_box({0.2, 0.2, 0.2}, {19.8, 19.8, 3.8});
  const TriangleBvh thick_bvh(thick.V, thick.F);
  const ContourCavity t = contour_cavity(thick, thick_bvh, thick_inner, options);
  check_printable(thick, thick_bvh, t, wall);
  CHECK(t.shells == 1);
}

TEST_CASE("the contoured cavity is the same for any thread count") {
  const Mesh outer = make_icosphere(10.0, 3);
  const Mesh inner = make_icosphere(8.0, 3);
  const TriangleBvh outer_bvh(outer.V, outer.F);
  ContourCavityOptions options;
  options.wall = 0.9;
  options.threads = 1;
  const ContourCavity one = contour_cavity(outer, outer_bvh, inner, options);
  options.threads = 3;
  const ContourCavity three = contour_cavity(outer, outer_bvh, inner, options);
  REQUIRE(one.cavity.V.rows() == three.cavity.V.rows());
  REQUIRE(one.cavity.F.rows() == three.cavity.F.rows());
  CHECK(one.cavity.V == three.cavity.V);
  CHECK(one.cavity.F == three.cavity.F);
}

TEST_CASE("a node cap that forces a grid coarser than the wall still gives a printable cavity") {
  // At 1500 nodes the spacing grows past the wall (√3·h > wall), and the margin grows with it so
  // that no grid edge reaches from a cavity node to the outer surface.
  const SphereInSphere spheres;
  const double wall = 1.0;
  ContourCavityOptions options;
  options.wall = wall;
  options.max_nodes = 1500;
  const ContourCavity c = contour_cavity(spheres.outer, spheres.outer_bvh, spheres.inner, options);
  REQUIRE(c.ok);
  CHECK(std::sqrt(3.0) * c.grid.spacing > wall);
  check_printable(spheres.outer, spheres.outer_bvh, c, wall);
  CHECK(c.shells == 1);
}

namespace {

// q(x) = |x − c|² − r² on the monomials [1, x, y, z, x², y², z², xy, yz, zx].
Vector10d ball_quadric(const Eigen::Vector3d& c, double r) {
  Vector10d q = Vector10d::Zero();
  q(0) = c.squaredNorm() - r * r;
  q.segment<3>(1) = -2.0 * c;
  q(4) = q(5) = q(6) = 1.0;
  return q;
}

}  // namespace

TEST_CASE("a quadric ball inside a sphere: the analytic ball within the grid's error, closed, embedded, the wall kept") {
  const SphereInSphere spheres;  // outer radius 10
  const Eigen::Vector3d centre(0.4, -0.3, 0.25);
  const double r = 6.0, wall = 1.0, pi = 3.141592653589793;
  ContourCavityOptions options;
  options.wall = wall;
  // Any common scale of the coefficients gives the same void.
  for (const double scale : {1.0, 1e-3}) {
    const ContourCavity c = contour_cavity(spheres.outer, spheres.outer_bvh, Vector10d(scale * ball_quadric(centre, r)), options);
    check_printable(spheres.outer, spheres.outer_bvh, c, wall);
    CHECK(c.shells == 1);
    // The wall does not bind (10 − 6 − 0.56 > wall + margin + a cell), so every vertex is a zero of
    // the linear interpolation of −q/|∇q| = (r² − ρ²)/(2ρ) along an edge of at most √3 h: within
    // a small fraction of h of the sphere, and the chords lose a little volume.
    const double h = c.grid.spacing;
    double worst = 0.0;
    for (Eigen::Index v = 0; v < c.cavity.V.rows(); ++v)
      worst = std::max(worst, std::fabs((c.cavity.V.row(v).transpose() - centre).norm() - r));
    CHECK(worst < 0.05 * h);
    const double volume = volume_integrals(c.cavity).values(kIntVolume);
    const double ball = 4.0 / 3.0 * pi * r * r * r;
    CHECK(volume <= ball * 1.0001);
    CHECK(volume >= ball * 0.98);
  }
}

TEST_CASE("a half-space quadric cuts a box's interior into the analytic slab") {
  const double L = 20.0, wall = 1.0, z0 = 8.3;
  const Mesh outer = make_box({0, 0, 0}, {L, L, L});
  const TriangleBvh outer_bvh(outer.V, outer.F);
  Vector10d q = Vector10d::Zero();
  q(0) = -z0;
  q(3) = 1.0;  // q = z − z0: the void is below z0
  ContourCavityOptions options;
  options.wall = wall;
  const ContourCavity c = contour_cavity(outer, outer_bvh, q, options);
  check_printable(outer, outer_bvh, c, wall);
  CHECK(c.shells == 1);
  // Where the outer surface binds, vertices sit on the wall (d_out is linear along every grid
  // edge near a face, so exactly there) or, next to a node kept as material because it lies within
  // 0.02 h of the wall, up to that much above it; the plane is linear, so it is met exactly; only
  // the twelve edges of the slab lose a prism of at most h²/2 in cross-section.
  const double h = c.grid.spacing;
  double lowest = L, highest = 0.0;
  for (Eigen::Index v = 0; v < c.cavity.V.rows(); ++v) {
    lowest = std::min(lowest, c.cavity.V(v, 2));
    highest = std::max(highest, c.cavity.V(v, 2));
  }
  CHECK(highest == doctest::Approx(z0).epsilon(1e-9));
  CHECK(lowest >= wall);
  CHECK(lowest <= wall + 0.02 * h + 1e-3 * wall);
  auto slab_at = [&](double level) { return (L - 2.0 * level) * (L - 2.0 * level) * (z0 - level); };
  const double far = wall + 0.02 * h + 1e-3 * wall;  // the most any face sits above the wall
  const double edges = 8.0 * (L - 2.0 * wall) + 4.0 * (z0 - wall);
  const double volume = volume_integrals(c.cavity).values(kIntVolume);
  CHECK(volume <= slab_at(wall) * (1.0 + 1e-9));
  CHECK(volume >= slab_at(far) - edges * h * h / 2.0);
  // Closer than that in fact: within 2% of the slab at the wall.
  CHECK(volume >= 0.98 * slab_at(wall));
}

TEST_CASE("the quadric cavity is the same for any thread count") {
  const SphereInSphere spheres;
  // A tilted ellipsoid (cross terms): q = x²/36 + y²/25 + z²/16 + 0.02 (xy + yz + zx) − 1.
  Vector10d q = Vector10d::Zero();
  q << -1.0, 0.1, 0.0, -0.05, 1.0 / 36, 1.0 / 25, 1.0 / 16, 0.02, 0.02, 0.02;
  ContourCavityOptions options;
  options.wall = 0.9;
  options.threads = 1;
  const ContourCavity one = contour_cavity(spheres.outer, spheres.outer_bvh, q, options);
  options.threads = 3;
  const ContourCavity three = contour_cavity(spheres.outer, spheres.outer_bvh, q, options);
  REQUIRE(one.ok);
  REQUIRE(one.cavity.F.rows() > 0);
  REQUIRE(one.cavity.V.rows() == three.cavity.V.rows());
  REQUIRE(one.cavity.F.rows() == three.cavity.F.rows());
  CHECK(one.cavity.V == three.cavity.V);
  CHECK(one.cavity.F == three.cavity.F);
}

TEST_CASE("quadric cavities contoured one after another with what they share kept: the same as each alone") {
  // Ellipsoids that reach past the wall (the wall binds on part of them, the quadric on the rest),
  // moved a little from one to the next as the quadric void's rounds move them, then a ball, then
  // another wall (another grid: nothing kept applies).
  const SphereInSphere spheres;
  Vector10d wide = Vector10d::Zero();
  wide << -1.0, 0.05, 0.0, -0.02, 1.0 / 100, 1.0 / 64, 1.0 / 36, 0.004, 0.004, 0.004;
  Vector10d moved = wide;
  moved(0) -= 0.03;
  moved(3) += 0.01;
  const Vector10d ball = ball_quadric(Eigen::Vector3d(0.4, -0.3, 0.25), 6.0);
  std::shared_ptr<ContourReuse> reuse;
  int compared = 0;
  for (const auto& [q, wall] : std::vector<std::pair<Vector10d, double>>{{wide, 0.9}, {moved, 0.9}, {moved, 0.9}, {ball, 0.9}, {wide, 1.1}}) {
    ContourCavityOptions options;
    options.wall = wall;
    const ContourCavity alone = contour_cavity(spheres.outer, spheres.outer_bvh, q, options);
    const ContourCavity kept = contour_cavity(spheres.outer, spheres.outer_bvh, q, options, &reuse);
    REQUIRE(alone.ok);
    REQUIRE(kept.ok);
    REQUIRE(alone.cavity.V.rows() == kept.cavity.V.rows());
    REQUIRE(alone.cavity.F.rows() == kept.cavity.F.rows());
    CHECK(alone.cavity.V == kept.cavity.V);
    CHECK(alone.cavity.F == kept.cavity.F);
    CHECK(alone.distance_nodes == kept.distance_nodes);
    CHECK(alone.vertices_moved_for_wall == kept.vertices_moved_for_wall);
    CHECK(alone.faces_lifted == kept.faces_lifted);
    compared += alone.vertices_moved_for_wall > 0;
  }
  CHECK(compared >= 3);  // the wall bound where it matters
}

TEST_CASE("a quadric with a non-finite coefficient is refused, not contoured") {
  const SphereInSphere spheres;
  Vector10d q = ball_quadric(Eigen::Vector3d::Zero(), 5.0);
  q(4) = std::numeric_limits<double>::quiet_NaN();
  ContourCavityOptions options;
  options.wall = 1.0;
  const ContourCavity c = contour_cavity(spheres.outer, spheres.outer_bvh, q, options);
  CHECK(!c.ok);
  CHECK(!c.message.empty());
}

namespace {

// An L-shaped prism: the square [0, 20]² less the notch [8, 20]², 12 high. Its reflex edge at
// x = y = 8 is where the wall-level set is a cylinder, whose chords dip below the wall.
Mesh make_l_prism() {
  const double xy[6][2] = {{0, 0}, {20, 0}, {20, 8}, {8, 8}, {8, 20}, {0, 20}};
  Mesh m;
  m.V.resize(12, 3);
  for (int i = 0; i < 6; ++i) {
    m.V.row(i) << xy[i][0], xy[i][1], 0.0;
    m.V.row(i + 6) << xy[i][0], xy[i][1], 12.0;
  }
  std::vector<std::array<int, 3>> faces;
  // Caps: a fan from the reflex corner (3), which sees the whole polygon.
  for (int k : {4, 5, 0, 1}) {
    faces.push_back({3, (k + 1) % 6, k});          // bottom, normal −z
    faces.push_back({9, 6 + k, 6 + (k + 1) % 6});  // top, normal +z
  }
  for (int i = 0; i < 6; ++i) {  // sides, counter-clockwise polygon: outward normals
    const int j = (i + 1) % 6;
    faces.push_back({i, j, 6 + j});
    faces.push_back({i, 6 + j, 6 + i});
  }
  m.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int c = 0; c < 3; ++c) m.F(static_cast<Eigen::Index>(f), c) = faces[f][static_cast<std::size_t>(c)];
  return m;
}

}  // namespace

TEST_CASE("an L-shaped solid hollowed whole: vertices on the wall, faces above it, the eroded volume") {
  const Mesh outer = make_l_prism();
  REQUIRE(volume_integrals(outer).values(kIntVolume) == doctest::Approx(12.0 * (400.0 - 144.0)));
  const TriangleBvh outer_bvh(outer.V, outer.F);
  const double wall = 1.5, pi = 3.141592653589793;
  Vector10d everywhere = Vector10d::Zero();
  everywhere(0) = -1.0;  // q < 0 everywhere (and |∇q| = 0): the void is all that keeps the wall
  ContourCavityOptions options;
  options.wall = wall;
  const ContourCavity c = contour_cavity(outer, outer_bvh, everywhere, options);
  check_printable(outer, outer_bvh, c, wall);
  CHECK(c.shells == 1);
  CHECK(c.faces_below_wall == 0);
  CHECK(c.demotions == 0);
  // The wall-bound vertices sit at the wall, not a margin above it.
  CHECK(smallest_wall(outer_bvh, c.cavity) <= wall * (1.0 + 1e-4));
  // Every face keeps the wall, sampled densely (exact closest points at 28 points of each face).
  double face_wall = std::numeric_limits<double>::infinity();
  for (Eigen::Index f = 0; f < c.cavity.F.rows(); ++f)
    for (int i = 0; i <= 6; ++i)
      for (int j = 0; i + j <= 6; ++j) {
        const Eigen::Vector3d a = c.cavity.V.row(c.cavity.F(f, 0)).transpose();
        const Eigen::Vector3d p = a + (i / 6.0) * (c.cavity.V.row(c.cavity.F(f, 1)).transpose() - a) +
                                  (j / 6.0) * (c.cavity.V.row(c.cavity.F(f, 2)).transpose() - a);
        face_wall = std::min(face_wall, closest_point(outer_bvh, p).distance);
      }
  CHECK(face_wall >= wall);
  // The eroded L: two strips less their overlap, plus the corner square less a quarter disc of
  // radius `wall` round the reflex edge; the contour lies inside it and loses only the grid's
  // chords along its edges.
  const double area = 2.0 * (20.0 - 2.0 * wall) * (8.0 - 2.0 * wall) - (8.0 - 2.0 * wall) * (8.0 - 2.0 * wall) +
                      wall * wall * (1.0 - pi / 4.0);
  const double eroded = area * (12.0 - 2.0 * wall);
  const double volume = volume_integrals(c.cavity).values(kIntVolume);
  CHECK(volume <= eroded * (1.0 + 1e-6));
  CHECK(volume >= eroded * 0.97);
  // The lifting was exercised: with the vertices on the wall, faces round the reflex edge dipped.
  CHECK(c.faces_lifted > 0);
  CHECK(c.largest_face_deficit > 0.0);
}
