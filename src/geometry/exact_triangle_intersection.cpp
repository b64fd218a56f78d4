#include "geometry/exact_triangle_intersection.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "geometry/convex_hull_2d.h"
#include "geometry/convex_hull_3d.h"

namespace offsetopt {

namespace {

using Vec3 = Eigen::Vector3d;
using Vec2 = Eigen::Vector2d;

int sign(double x) { return x > 0.0 ? 1 : x < 0.0 ? -1 : 0; }

int sign(long double x) { return x > 0.0L ? 1 : x < 0.0L ? -1 : 0; }

Vec2 drop(const Vec3& p, int axis) {
  switch (axis) {
    case 0: return {p.y(), p.z()};
    case 1: return {p.z(), p.x()};
    default: return {p.x(), p.y()};
  }
}

// An axis whose projection keeps the triangle's area exactly non-zero, or -1 when the corners
// are collinear. Dropping axis k leaves the k-th component of the normal as the projected area,
// so the axes are tried from the largest component of the rounded normal: the first is almost
// always it, decided by orient2d's floating-point filter.
int plane_axis(const Vec3& p, const Vec3& q, const Vec3& r) {
  const Vec3 n = (q - p).cross(r - p).cwiseAbs();
  const int first = n.x() >= n.y() ? (n.x() >= n.z() ? 0 : 2) : (n.y() >= n.z() ? 1 : 2);
  const int order[3] = {first, (first + 1) % 3, (first + 2) % 3};
  for (const int axis : order)
    if (orient2d_sign(drop(p, axis), drop(q, axis), drop(r, axis)) != 0) return axis;
  return -1;
}

bool in_box(const Vec2& a, const Vec2& b, const Vec2& p) {
  return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) && std::min(a.y(), b.y()) <= p.y() &&
         p.y() <= std::max(a.y(), b.y());
}

// Closed segments a-b and c-d of the plane (neither a point) share a point.
bool segments_meet_2d(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const int o1 = orient2d_sign(a, b, c), o2 = orient2d_sign(a, b, d);
  const int o3 = orient2d_sign(c, d, a), o4 = orient2d_sign(c, d, b);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  // A point exactly on the other segment's line: on it when inside its bounding box.
  return (o1 == 0 && in_box(a, b, c)) || (o2 == 0 && in_box(a, b, d)) || (o3 == 0 && in_box(c, d, a)) ||
         (o4 == 0 && in_box(c, d, b));
}

// x in the closed triangle t (t not collinear).
bool point_in_triangle_2d(const Vec2& x, const Vec2 t[3]) {
  const int turn = orient2d_sign(t[0], t[1], t[2]);
  for (int k = 0; k < 3; ++k)
    if (orient2d_sign(t[k], t[(k + 1) % 3], x) * turn < 0) return false;
  return true;
}

// Segment a-b lying in the plane of triangle p-q-r.
bool coplanar_segment_meets_triangle(const Vec3& a, const Vec3& b, const Vec3& p, const Vec3& q, const Vec3& r) {
  const int axis = plane_axis(p, q, r);
  const Vec2 t[3] = {drop(p, axis), drop(q, axis), drop(r, axis)};
  const Vec2 a2 = drop(a, axis), b2 = drop(b, axis);
  if (point_in_triangle_2d(a2, t) || point_in_triangle_2d(b2, t)) return true;
  for (int k = 0; k < 3; ++k)
    if (segments_meet_2d(a2, b2, t[k], t[(k + 1) % 3])) return true;
  return false;
}

}  // namespace

namespace {

// Seen along axis k, the four points fall on at most two points of the plane: they lie in a plane
// parallel to axis k (three of them on one axis-parallel line is a case of it).
bool two_projections(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, int k) {
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  auto same = [&](const Vec3& p, const Vec3& q) { return p[i] == q[i] && p[j] == q[j]; };
  const Vec3* second = nullptr;
  for (const Vec3* p : {&b, &c, &d}) {
    if (same(*p, a)) continue;
    if (!second) second = p;
    else if (!same(*p, *second)) return false;
  }
  return true;
}

// The extended-precision filters below assume a 64-bit significand. Where long double is a
// double (MSVC) or is computed as one (valgrind emulates x87 arithmetic in double precision),
// their bounds do not hold: there the filter is skipped and the exact expansions decide.
bool extended_precision() {
  static const bool holds = [] {
    volatile long double one = 1.0L, tiny = 0x1p-60L;
    const long double sum = one + tiny;
    return sum != one;
  }();
  return holds;
}

// p + q == r + s exactly (each sum as its rounded value and the exact error of the rounding: two
// sums are equal exactly when both parts are).
bool same_sum(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s) {
  for (int k = 0; k < 3; ++k) {
    const double x = p[k] + q[k], y = r[k] + s[k];
    if (x != y) return false;
    const double xv = x - p[k], yv = y - r[k];
    if ((p[k] - (x - xv)) + (q[k] - xv) != (r[k] - (y - yv)) + (s[k] - yv)) return false;
  }
  return true;
}

// Zero determinants that comparisons decide: the four points on one axis-aligned plane, or on a
// plane parallel to an axis through two stacks of vertices (three on one axis-parallel line is
// such a case), or a parallelogram. Real inputs are full of them (a posed base at z = 0, the
// vertical and sloped quads of a turned or extruded surface, contoured cavities on grid planes),
// and each would otherwise go through both filters and the exact expansions (the buoy's quads:
// 2·10⁵ exact zeros a run, the bottle's 8·10⁴).
bool exactly_degenerate(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  for (int k = 0; k < 3; ++k)
    if (a[k] == b[k] && a[k] == c[k] && a[k] == d[k]) return true;
  for (int k = 0; k < 3; ++k)
    if (two_projections(a, b, c, d, k)) return true;
  // A parallelogram (an edge and its translate: the sloped quads of a turned surface whose rings
  // are moved copies of each other) is flat.
  return same_sum(a, b, c, d) || same_sum(a, c, b, d) || same_sum(a, d, b, c);
}

}  // namespace

namespace {

// orient3d_sign past its floating-point filter: the comparisons, the extended-precision filter,
// the exact expansions.
int orient3d_sign_unfiltered(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  if (exactly_degenerate(a, b, c, d)) return 0;
  if (!extended_precision()) return sign(orient3d(a, b, c, d));
  // The same evaluation in x87 extended precision (unit roundoff 2^-64): Shewchuk's bound for it
  // is (7 + 56 eps) eps = 3.8e-19 of the permanent; 1e-18 leaves a margin.
  long double U[3], W[3], X[3];
  for (int k = 0; k < 3; ++k) {
    U[k] = static_cast<long double>(b[k]) - static_cast<long double>(a[k]);
    W[k] = static_cast<long double>(c[k]) - static_cast<long double>(a[k]);
    X[k] = static_cast<long double>(d[k]) - static_cast<long double>(a[k]);
  }
  const long double m0 = W[1] * X[2] - W[2] * X[1], m1 = W[0] * X[2] - W[2] * X[0], m2 = W[0] * X[1] - W[1] * X[0];
  const long double det_l = U[0] * m0 - U[1] * m1 + U[2] * m2;
  auto mag = [](long double x) { return x < 0.0L ? -x : x; };
  const long double permanent_l = mag(U[0]) * (mag(W[1] * X[2]) + mag(W[2] * X[1])) +
                                  mag(U[1]) * (mag(W[0] * X[2]) + mag(W[2] * X[0])) +
                                  mag(U[2]) * (mag(W[0] * X[1]) + mag(W[1] * X[0]));
  if (mag(det_l) > 1e-18L * permanent_l) return sign(det_l);
  return sign(orient3d(a, b, c, d));
}

}  // namespace

int orient3d_sign(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 u = b - a, v = c - a, w = d - a;
  const double det = u.x() * (v.y() * w.z() - v.z() * w.y()) - u.y() * (v.x() * w.z() - v.z() * w.x()) +
                     u.z() * (v.x() * w.y() - v.y() * w.x());
  const double permanent = std::fabs(u.x()) * (std::fabs(v.y() * w.z()) + std::fabs(v.z() * w.y())) +
                           std::fabs(u.y()) * (std::fabs(v.x() * w.z()) + std::fabs(v.z() * w.x())) +
                           std::fabs(u.z()) * (std::fabs(v.x() * w.y()) + std::fabs(v.y() * w.x()));
  if (std::fabs(det) > 1e-14 * permanent) return sign(det);
  return orient3d_sign_unfiltered(a, b, c, d);
}

PlaneSide::PlaneSide(const Vec3& a, const Vec3& b, const Vec3& c) : a_(a), b_(b), c_(c) {
  const Vec3 u = b - a, v = c - a;
  normal_ = Vec3(u.y() * v.z() - u.z() * v.y(), u.z() * v.x() - u.x() * v.z(), u.x() * v.y() - u.y() * v.x());
  bound_ = Vec3(std::fabs(u.y() * v.z()) + std::fabs(u.z() * v.y()), std::fabs(u.z() * v.x()) + std::fabs(u.x() * v.z()),
                std::fabs(u.x() * v.y()) + std::fabs(u.y() * v.x()));
}

int PlaneSide::operator()(const Vec3& d) const {
  // det[u; v; w] = (u × v) · w, and its permanent the same six products |u_i v_j w_k|: the
  // filter of orient3d_sign, expanded along w instead of u.
  const Vec3 w = d - a_;
  const double det = normal_.x() * w.x() + normal_.y() * w.y() + normal_.z() * w.z();
  const double permanent = bound_.x() * std::fabs(w.x()) + bound_.y() * std::fabs(w.y()) + bound_.z() * std::fabs(w.z());
  if (std::fabs(det) > 1e-14 * permanent) return sign(det);
  // Past orient3d_sign's own filter too (a sign it decides is the exact sign either way).
  return orient3d_sign_unfiltered(a_, b_, c_, d);
}

int orient2d_sign(const Vec2& a, const Vec2& b, const Vec2& c) {
  const double left = (a.x() - c.x()) * (b.y() - c.y()), right = (a.y() - c.y()) * (b.x() - c.x());
  if (std::fabs(left - right) > 3.3306690738754716e-16 * (std::fabs(left) + std::fabs(right))) return sign(left - right);
  if (!extended_precision()) return sign(orient2d(a, b, c));
  // Extended precision: (3 + 16 eps) eps = 1.6e-19 with eps = 2^-64.
  const long double l = (static_cast<long double>(a.x()) - c.x()) * (static_cast<long double>(b.y()) - c.y());
  const long double r = (static_cast<long double>(a.y()) - c.y()) * (static_cast<long double>(b.x()) - c.x());
  const long double magnitude = (l < 0.0L ? -l : l) + (r < 0.0L ? -r : r);
  const long double difference = l - r;
  if ((difference < 0.0L ? -difference : difference) > 1e-18L * magnitude) return sign(difference);
  return sign(orient2d(a, b, c));
}

bool collinear_exact(const Vec3& p, const Vec3& q, const Vec3& r) { return plane_axis(p, q, r) < 0; }

namespace {

// The segment test once the sides of its ends (orient3d signs against the triangle's plane) are
// known.
bool segment_with_sides_meets_triangle(const Vec3& a, const Vec3& b, int oa, int ob, const Vec3& p, const Vec3& q,
                                       const Vec3& r) {
  if (oa * ob > 0) return false;  // both strictly on one side
  if (oa == 0 && ob == 0) return coplanar_segment_meets_triangle(a, b, p, q, r);
  // The segment reaches the plane at one point (an end, or between the ends), and the line a-b
  // is not in the plane: it passes through the closed triangle iff it passes no two of its
  // edges on opposite sides.
  const int s1 = orient3d_sign(a, b, p, q), s2 = orient3d_sign(a, b, q, r);
  if (s1 * s2 < 0) return false;
  const int s3 = orient3d_sign(a, b, r, p);
  const bool negative = s1 < 0 || s2 < 0 || s3 < 0, positive = s1 > 0 || s2 > 0 || s3 > 0;
  return !(negative && positive);
}

}  // namespace

bool segment_meets_triangle_exact(const Vec3& a, const Vec3& b, const Vec3& p, const Vec3& q, const Vec3& r) {
  const int oa = orient3d_sign(p, q, r, a);
  const int ob = orient3d_sign(p, q, r, b);
  return segment_with_sides_meets_triangle(a, b, oa, ob, p, q, r);
}

bool segment_meets_triangle_exact(const Vec3& a, const Vec3& b, int side_a, int side_b, const Vec3& p, const Vec3& q,
                                  const Vec3& r) {
  return segment_with_sides_meets_triangle(a, b, side_a, side_b, p, q, r);
}

bool coplanar_fan_pair_meets(const Vec3& v, const Vec3& f1, const Vec3& f2, const Vec3& g1, const Vec3& g2) {
  // In a projection that keeps f's area every point of the plane keeps its orientations. Near v
  // each face is its wedge (the cone at v spanned by its two edges from v, narrower than a half
  // plane), so the faces share a point other than v exactly when the wedges share a ray; and then
  // a boundary ray of one wedge lies in the other (the boundary rays of their common cone are
  // theirs). Either far edge meeting the other face is the same as the faces sharing a point
  // other than v (from v towards such a point, the common part is left through a far edge), so
  // the rule needs 6 orient2d signs, where the two segment tests took about 40.
  const int axis = plane_axis(v, f1, f2);
  const Vec2 V = drop(v, axis), F1 = drop(f1, axis), F2 = drop(f2, axis), G1 = drop(g1, axis), G2 = drop(g2, axis);
  const int turn_f = orient2d_sign(V, F1, F2), turn_g = orient2d_sign(V, G1, G2);
  // The rays from v: o(v, g, f) = −o(v, f, g).
  const int f1_g1 = orient2d_sign(V, F1, G1), f1_g2 = orient2d_sign(V, F1, G2);
  const int f2_g1 = orient2d_sign(V, F2, G1), f2_g2 = orient2d_sign(V, F2, G2);
  // Ray u in the wedge of rays a, b turning `turn` from a to b: o(v, a, u) and o(v, u, b) not
  // against the turn (a wedge narrower than a half plane holds no ray opposite to its own).
  auto within = [](int a_u, int u_b, int turn) { return a_u * turn >= 0 && u_b * turn >= 0; };
  return within(f1_g1, -f2_g1, turn_f) || within(f1_g2, -f2_g2, turn_f) || within(-f1_g1, f1_g2, turn_g) ||
         within(-f2_g1, f2_g2, turn_g);
}

namespace {

// Closed triangles a and b of one plane (neither collinear): disjoint exactly when the line of
// one of their six edges has the other triangle strictly outside (separating axes, as in
// coplanar_fan_pair_meets). At most 20 orient2d signs, where the six segment tests took ~130.
bool coplanar_triangles_meet(const Vec3 a[3], const Vec3 b[3]) {
  const int axis = plane_axis(b[0], b[1], b[2]);
  const Vec2 A[3] = {drop(a[0], axis), drop(a[1], axis), drop(a[2], axis)};
  const Vec2 B[3] = {drop(b[0], axis), drop(b[1], axis), drop(b[2], axis)};
  auto separated = [](const Vec2 t[3], const Vec2 other[3]) {
    const int turn = orient2d_sign(t[0], t[1], t[2]);
    for (int k = 0; k < 3; ++k) {
      const Vec2 &p = t[k], &q = t[(k + 1) % 3];
      if (orient2d_sign(p, q, other[0]) * turn < 0 && orient2d_sign(p, q, other[1]) * turn < 0 &&
          orient2d_sign(p, q, other[2]) * turn < 0)
        return true;
    }
    return false;
  };
  return !separated(A, B) && !separated(B, A);
}

}  // namespace

bool triangles_meet_exact(const Vec3 a[3], const Vec3 b[3]) {
  auto one_side = [](const int s[3]) { return (s[0] > 0 && s[1] > 0 && s[2] > 0) || (s[0] < 0 && s[1] < 0 && s[2] < 0); };
  // One plane at a time: most pairs a search tests are apart, and the first plane usually shows it.
  int side_a[3], side_b[3];
  const PlaneSide plane_b(b[0], b[1], b[2]);
  for (int k = 0; k < 3; ++k) side_a[k] = plane_b(a[k]);
  if (one_side(side_a)) return false;
  if (side_a[0] == 0 && side_a[1] == 0 && side_a[2] == 0) return coplanar_triangles_meet(a, b);
  const PlaneSide plane_a(a[0], a[1], a[2]);
  for (int k = 0; k < 3; ++k) side_b[k] = plane_a(b[k]);
  if (one_side(side_b)) return false;
  // Two closed triangles meet iff an edge of one meets the other: where their planes cross, the
  // common part ends on an edge of one of them; where they are coplanar, edges cross or one
  // triangle holds the other, whose edges then lie in it.
  for (int k = 0; k < 3; ++k) {
    const int j = (k + 1) % 3;
    if (segment_with_sides_meets_triangle(a[k], a[j], side_a[k], side_a[j], b[0], b[1], b[2])) return true;
    if (segment_with_sides_meets_triangle(b[k], b[j], side_b[k], side_b[j], a[0], a[1], a[2])) return true;
  }
  return false;
}

}  // namespace offsetopt
