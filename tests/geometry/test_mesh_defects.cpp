// Pair tests behind `check`'s self-intersection search on the configurations that broke plain
// Guigue-Devillers: a zero-area triangle (no plane) far from a triangle it overlaps in
// projection, faces of one cone strip whose corners lie exactly on each other's planes, and a
// T-junction closed by a sliver. Expected answers are by construction.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "geometry/exact_triangle_intersection.h"
#include "geometry/mesh_defects.h"
#include "geometry/triangle_triangle.h"
#include "geometry/faces_intersect_exact.h"
#include "mesh/demo_meshes.h"
#include "mesh/primitives.h"
#include "util/rng.h"

using namespace offsetopt;
using V3 = Eigen::Vector3d;

TEST_CASE("a zero-area triangle is tested as its three edges, not in a 2-D projection") {
  const V3 p(0, 0, 0), q(4, 0, 0), r(0, 4, 0);
  // Collinear corners 5 units above the triangle, right over it: no contact.
  CHECK_FALSE(triangles_intersect(p, q, r, V3(1, 1, 5), V3(2, 1, 5), V3(3, 1, 5)));
  CHECK_FALSE(triangles_intersect(V3(1, 1, 5), V3(2, 1, 5), V3(3, 1, 5), p, q, r));
  // Collinear corners on a vertical segment through the triangle: contact.
  CHECK(triangles_intersect(p, q, r, V3(1, 1, -1), V3(1, 1, 0.5), V3(1, 1, 2)));
  CHECK(triangles_intersect(V3(1, 1, -1), V3(1, 1, 0.5), V3(1, 1, 2), p, q, r));
}

TEST_CASE("two faces of one cone strip, corners on each other's planes, do not meet") {
  // Four faces between two rulings of a cone (apex at the origin): the rulings' points are
  // coplanar, and faces 0 and 2 share no corner.
  Mesh strip;
  strip.V.resize(6, 3);
  const V3 a(3, 0, 3), b(2.9, 0.7, 3);  // two rulings through the apex: k * a, k * b
  for (int k = 1; k <= 3; ++k) {
    strip.V.row(2 * (k - 1)) = (k * a).transpose();
    strip.V.row(2 * (k - 1) + 1) = (k * b).transpose();
  }
  strip.F.resize(4, 3);
  strip.F << 0, 1, 3, 0, 3, 2, 2, 3, 5, 2, 5, 4;
  CHECK(find_self_intersections(strip).pairs == 0);
}

TEST_CASE("the demo bottle, top and buoy have no self-intersecting pairs") {
  for (const char* name : {"bottle", "top", "buoy"}) {
    CAPTURE(name);
    CHECK(find_self_intersections(make_demo_mesh(name)).pairs == 0);
  }
}

TEST_CASE("triangles_meet_exact: the demo bottle's cone-strip pair that plain Guigue-Devillers reports one way round") {
  // Faces 1056 and 1185 of the demo bottle: three corners on each of two rulings of a cone, so
  // a corner of each lies on the other's plane up to rounding; they are 3.4 apart in that plane.
  const V3 f[3] = {V3(1.7999999999999936, -35, 4), V3(5.2305999115346031, -34.831465433526894, 4),
                   V3(9.3368499115346033, -34.831465433526894, 13.125)};
  const V3 g[3] = {V3(5.9062499999999938, -35, 13.125), V3(13.443099911534604, -34.831465433526894, 22.25),
                   V3(10.012499999999994, -35, 22.25)};
  CHECK_FALSE(triangles_meet_exact(f, g));
  CHECK_FALSE(triangles_meet_exact(g, f));
  // Exactly coplanar (z = 0) and overlapping, touching at one point, and 2^-40 apart.
  const V3 t[3] = {V3(0, 0, 0), V3(4, 0, 0), V3(0, 4, 0)};
  const V3 overlap[3] = {V3(1, 1, 0), V3(5, 1, 0), V3(1, 5, 0)};
  const V3 touch[3] = {V3(2, 2, 0), V3(5, 2, 0), V3(2, 5, 0)};  // (2, 2) is on the edge x + y = 4
  const V3 apart[3] = {V3(2, 2.0 + std::ldexp(1.0, -40), 0), V3(5, 2, 0), V3(2, 5, 0)};
  CHECK(triangles_meet_exact(t, overlap));
  CHECK(triangles_meet_exact(t, touch));
  CHECK(triangles_meet_exact(touch, t));
  CHECK_FALSE(triangles_meet_exact(t, apart));
  CHECK_FALSE(triangles_meet_exact(apart, t));
  // A clear crossing and a clear miss.
  const V3 crossing[3] = {V3(1, 1, -1), V3(1, 1.5, 2), V3(1.5, 1, 2)};
  const V3 above[3] = {V3(1, 1, 1), V3(1, 1.5, 2), V3(1.5, 1, 2)};
  CHECK(triangles_meet_exact(t, crossing));
  CHECK_FALSE(triangles_meet_exact(t, above));
}

namespace {

// Two faces as a mesh of their own (find_self_intersections needs no closed surface).
long long pairs_of(const std::vector<V3>& points, const std::vector<std::array<int, 3>>& faces) {
  Mesh m;
  m.V.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) m.V.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  m.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    m.F.row(static_cast<Eigen::Index>(f)) << faces[f][0], faces[f][1], faces[f][2];
  return find_self_intersections(m).pairs;
}

// Faces (v, f1, f2) and (v, g1, g2) as faces_intersect_exact takes them (corners and their
// vertex indices 0..4), each turned so the shared corner v stands at position `shift_f` of the
// first face and `shift_g` of the second.
struct FacePair {
  V3 a[3], b[3];
  int ia[3], ib[3];
};
FacePair turned_pair(const V3& v, const V3& f1, const V3& f2, const V3& g1, const V3& g2, int shift_f, int shift_g) {
  FacePair pair;
  const V3 fa[3] = {v, f1, f2}, gb[3] = {v, g1, g2};
  const int fi[3] = {0, 1, 2}, gi[3] = {0, 3, 4};
  for (int k = 0; k < 3; ++k) {
    pair.a[k] = fa[(k + shift_f) % 3];
    pair.ia[k] = fi[(k + shift_f) % 3];
    pair.b[k] = gb[(k + shift_g) % 3];
    pair.ib[k] = gi[(k + shift_g) % 3];
  }
  return pair;
}

}  // namespace

TEST_CASE("check's pair rule on hand-built pairs: touching along an edge or at a corner, or coplanar and adjacent, is no pair, crossing, folding and touching apart are") {
  const double tiny = std::ldexp(1.0, -40);
  // A common edge 0-1, the third corners on opposite sides in one plane: one flat surface.
  CHECK(pairs_of({V3(0, 0, 0), V3(4, 0, 0), V3(2, 3, 0), V3(2, -3, 0)}, {{0, 1, 2}, {1, 0, 3}}) == 0);
  // ... on the same side in one plane: folded onto each other.
  CHECK(pairs_of({V3(0, 0, 0), V3(4, 0, 0), V3(2, 3, 0), V3(1, 1, 0)}, {{0, 1, 2}, {1, 0, 3}}) == 1);
  // ... a hinge (not coplanar), however sharp.
  CHECK(pairs_of({V3(0, 0, 0), V3(4, 0, 0), V3(2, 3, 0), V3(2, 3, tiny)}, {{0, 1, 2}, {1, 0, 3}}) == 0);
  // A common corner only, coplanar, the faces on either side of it: a bow tie.
  CHECK(pairs_of({V3(0, 0, 0), V3(2, 1, 0), V3(2, -1, 0), V3(-2, 1, 0), V3(-2, -1, 0)}, {{0, 1, 2}, {0, 4, 3}}) == 0);
  // ... overlapping beyond the corner.
  CHECK(pairs_of({V3(0, 0, 0), V3(2, 1, 0), V3(2, -1, 0), V3(3, 2, 0), V3(3, 0, 0)}, {{0, 1, 2}, {0, 4, 3}}) == 1);
  // ... the second's opposite edge through the first's interior (not coplanar).
  CHECK(pairs_of({V3(0, 0, 0), V3(4, 0, 0), V3(0, 4, 0), V3(1, 1, -1), V3(1, 1, 1)}, {{0, 1, 2}, {0, 3, 4}}) == 1);
  // No common corner: a corner of one exactly on the other's edge (closed triangles touch).
  CHECK(pairs_of({V3(0, 0, 0), V3(4, 0, 0), V3(0, 4, 0), V3(2, 2, 0), V3(5, 2, 0), V3(2, 5, 0)}, {{0, 1, 2}, {3, 4, 5}}) == 1);
  // ... coplanar and 2^-40 apart.
  CHECK(pairs_of({V3(0, 0, 0), V3(4, 0, 0), V3(0, 4, 0), V3(2, 2 + tiny, 0), V3(5, 2, 0), V3(2, 5, 0)}, {{0, 1, 2}, {3, 4, 5}}) == 0);
  // ... crossing.
  CHECK(pairs_of({V3(0, 0, 0), V3(4, 0, 0), V3(0, 4, 0), V3(1, 1, -1), V3(1, 1.5, 2), V3(1.5, 1, 2)}, {{0, 1, 2}, {3, 4, 5}}) == 1);
  // Corners at one position are one corner: two faces meeting at a welded corner only.
  CHECK(pairs_of({V3(0, 0, 0), V3(2, 1, 0), V3(2, -1, 0), V3(0, 0, 0), V3(-2, 1, 1), V3(-2, -1, 1)}, {{0, 1, 2}, {3, 4, 5}}) == 0);
}

TEST_CASE("find_self_intersections on two threads: the report of one thread, and every pair an all-pairs loop finds") {
  // Two overlapping icospheres as one mesh (no shared vertices): their crossing faces are pairs.
  const Mesh one = make_icosphere(1.0, 2);
  Mesh both;
  both.V.resize(2 * one.V.rows(), 3);
  both.F.resize(2 * one.F.rows(), 3);
  both.V << one.V, (one.V.rowwise() + Eigen::RowVector3d(0.9, 0.13, 0.07));
  both.F << one.F, (one.F.array() + static_cast<int>(one.V.rows())).matrix();
  long long all_pairs = 0;
  std::pair<int, int> first{-1, -1};
  for (Eigen::Index f = 0; f < both.F.rows(); ++f)
    for (Eigen::Index g = f + 1; g < both.F.rows(); ++g) {
      V3 a[3], b[3];
      int ia[3], ib[3];
      for (int k = 0; k < 3; ++k) {
        ia[k] = both.F(f, k);
        ib[k] = both.F(g, k);
        a[k] = both.V.row(ia[k]).transpose();
        b[k] = both.V.row(ib[k]).transpose();
      }
      if (!faces_intersect_exact(a, ia, b, ib)) continue;
      if (all_pairs++ == 0) first = {static_cast<int>(f), static_cast<int>(g)};
    }
  REQUIRE(all_pairs > 0);
  const SelfIntersectionReport serial = find_self_intersections(both, 1000000, 1);
  const SelfIntersectionReport parallel = find_self_intersections(both, 1000000, 2);
  CHECK(serial.pairs == all_pairs);
  CHECK(std::make_pair(serial.first_face, serial.second_face) == first);
  CHECK(parallel.pairs == serial.pairs);
  CHECK(parallel.first_face == serial.first_face);
  CHECK(parallel.second_face == serial.second_face);
  CHECK(parallel.candidate_pairs == serial.candidate_pairs);
  CHECK(!parallel.truncated);
  // A cap below the count: the search stops where the one-thread search stops.
  const SelfIntersectionReport capped1 = find_self_intersections(both, 7, 1), capped2 = find_self_intersections(both, 7, 2);
  CHECK(capped1.truncated);
  CHECK(capped2.truncated);
  CHECK(capped2.pairs == capped1.pairs);
  CHECK(capped2.first_face == capped1.first_face);
  CHECK(capped2.second_face == capped1.second_face);
  CHECK(capped2.candidate_pairs == capped1.candidate_pairs);
}

TEST_CASE("coplanar faces on one vertex: the 2-D fan test agrees with the two exact segment tests") {
  // Points of a plane with integer coordinates (exactly coplanar, and on a small grid full of
  // collinear triples, touching corners and overlapping edges), on tilted and axis-aligned planes,
  // and random points of a horizontal plane (a flat top in general position).
  Rng rng(2611);
  auto integer = [&](int n) { return static_cast<double>(static_cast<int>(rng.below(2 * n + 1)) - n); };
  int meets = 0, misses = 0;
  for (int trial = 0; trial < 40000; ++trial) {
    const int kind = trial % 3;
    V3 origin(integer(5), integer(5), integer(5)), u(1, 0, 0), w(0, 1, 0);
    if (kind == 1) {
      u = V3(integer(3), integer(3), integer(3));
      w = V3(integer(3), integer(3), integer(3));
      if (u.cross(w).squaredNorm() == 0.0) continue;
    }
    V3 p[5];
    for (V3& x : p) {
      if (kind == 2) x = V3(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), 0.375);
      else x = origin + integer(3) * u + integer(3) * w;
    }
    const V3 &v = p[0], &f1 = p[1], &f2 = p[2], &g1 = p[3], &g2 = p[4];
    if (collinear_exact(v, f1, f2) || collinear_exact(v, g1, g2)) continue;
    const bool slow = segment_meets_triangle_exact(g1, g2, v, f1, f2) || segment_meets_triangle_exact(f1, f2, v, g1, g2);
    CAPTURE(trial);
    CHECK(coplanar_fan_pair_meets(v, f1, f2, g1, g2) == slow);
    // Through the pair rule, with the shared corner at every position of either face.
    const FacePair t = turned_pair(v, f1, f2, g1, g2, trial % 3, (trial / 3) % 3);
    if (f1 != g1 && f1 != g2 && f2 != g1 && f2 != g2) CHECK(faces_intersect_exact(t.a, t.ia, t.b, t.ib) == slow);
    ++(slow ? meets : misses);
  }
  CHECK(meets > 1000);
  CHECK(misses > 1000);
}

TEST_CASE("coplanar triangles: the 2-D separating-edge test agrees with the six exact segment tests") {
  Rng rng(2612);
  auto integer = [&](int n) { return static_cast<double>(static_cast<int>(rng.below(2 * n + 1)) - n); };
  int meets = 0, misses = 0;
  for (int trial = 0; trial < 40000; ++trial) {
    const int kind = trial % 3;
    V3 origin(integer(5), integer(5), integer(5)), u(0, 1, 0), w(0, 0, 1);
    if (kind == 1) {
      u = V3(integer(3), integer(3), integer(3));
      w = V3(integer(3), integer(3), integer(3));
      if (u.cross(w).squaredNorm() == 0.0) continue;
    }
    V3 a[3], b[3];
    for (V3* t : {a, b})
      for (int k = 0; k < 3; ++k) {
        if (kind == 2) t[k] = V3(rng.uniform(-1.0, 1.0), -0.625, rng.uniform(-1.0, 1.0));
        else t[k] = origin + integer(3) * u + integer(3) * w;
      }
    if (collinear_exact(a[0], a[1], a[2]) || collinear_exact(b[0], b[1], b[2])) continue;
    bool slow = false;
    for (int k = 0; k < 3 && !slow; ++k)
      slow = segment_meets_triangle_exact(a[k], a[(k + 1) % 3], b[0], b[1], b[2]) ||
             segment_meets_triangle_exact(b[k], b[(k + 1) % 3], a[0], a[1], a[2]);
    CAPTURE(trial);
    CHECK(triangles_meet_exact(a, b) == slow);
    CHECK(triangles_meet_exact(b, a) == slow);
    ++(slow ? meets : misses);
  }
  CHECK(meets > 1000);
  CHECK(misses > 1000);
}

TEST_CASE("faces on one vertex in space: the pair rule agrees with the two exact segment tests") {
  // The rule's shortcuts (far edges whose boxes miss the other face, the 2-D fan test when the
  // faces are coplanar) against its definition: f's far edge meets g or g's far edge meets f.
  // Integer points of a small 3-D grid (touching, collinear, coplanar and axis-aligned cases by
  // the thousand), of one tilted plane, and random points, around one corner at every position.
  Rng rng(2613);
  auto integer = [&](int n) { return static_cast<double>(static_cast<int>(rng.below(2 * n + 1)) - n); };
  int meets = 0, misses = 0, coplanar = 0;
  for (int trial = 0; trial < 60000; ++trial) {
    const int kind = trial % 4;
    V3 p[5];
    const V3 u(1, 2, -1), w(-2, 1, 3);
    for (V3& x : p) {
      if (kind == 0) x = V3(integer(2), integer(2), integer(2));
      else if (kind == 1) x = V3(integer(4), integer(4), integer(1));
      else if (kind == 2) x = integer(3) * u + integer(3) * w;
      else x = V3(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0));
    }
    const V3 &v = p[0], &f1 = p[1], &f2 = p[2], &g1 = p[3], &g2 = p[4];
    if (collinear_exact(v, f1, f2) || collinear_exact(v, g1, g2)) continue;
    // Exactly one common corner: the far corners differ from each other's.
    if (f1 == g1 || f1 == g2 || f2 == g1 || f2 == g2) continue;
    const bool slow = segment_meets_triangle_exact(g1, g2, v, f1, f2) || segment_meets_triangle_exact(f1, f2, v, g1, g2);
    const FacePair t = turned_pair(v, f1, f2, g1, g2, trial % 3, (trial / 3) % 3);
    CAPTURE(trial);
    CHECK(faces_intersect_exact(t.a, t.ia, t.b, t.ib) == slow);
    CHECK(faces_intersect_exact(t.b, t.ib, t.a, t.ia) == slow);
    ++(slow ? meets : misses);
    if (orient3d_sign(v, f1, f2, g1) == 0 && orient3d_sign(v, f1, f2, g2) == 0) ++coplanar;
  }
  CHECK(meets > 2000);
  CHECK(misses > 2000);
  CHECK(coplanar > 2000);
}
