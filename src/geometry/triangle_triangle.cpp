#include "geometry/triangle_triangle.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/closest_point.h"

namespace offsetopt {

namespace {

using Vec3 = Eigen::Vector3d;
using Vec2 = Eigen::Vector2d;

// Sign-carrying 2-D orientation: > 0 when a, b, c turn counter-clockwise.
double orient2d(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (a.x() - c.x()) * (b.y() - c.y()) - (a.y() - c.y()) * (b.x() - c.x());
}

bool on_segment_2d(const Vec2& a, const Vec2& b, const Vec2& p) {
  return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) && std::min(a.y(), b.y()) <= p.y() &&
         p.y() <= std::max(a.y(), b.y());
}

bool segments_intersect_2d(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double o1 = orient2d(a, b, c), o2 = orient2d(a, b, d), o3 = orient2d(c, d, a), o4 = orient2d(c, d, b);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) return true;
  if (o1 == 0 && on_segment_2d(a, b, c)) return true;
  if (o2 == 0 && on_segment_2d(a, b, d)) return true;
  if (o3 == 0 && on_segment_2d(c, d, a)) return true;
  if (o4 == 0 && on_segment_2d(c, d, b)) return true;
  return false;
}

bool point_in_triangle_2d(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  const double d1 = orient2d(a, b, p), d2 = orient2d(b, c, p), d3 = orient2d(c, a, p);
  const bool has_negative = d1 < 0 || d2 < 0 || d3 < 0;
  const bool has_positive = d1 > 0 || d2 > 0 || d3 > 0;
  return !(has_negative && has_positive);
}

// Drops the coordinate along which `normal` is largest (lowest index on ties).
Vec2 project(const Vec3& p, int dropped_axis) {
  switch (dropped_axis) {
    case 0: return {p.y(), p.z()};
    case 1: return {p.z(), p.x()};
    default: return {p.x(), p.y()};
  }
}

int dominant_axis(const Vec3& normal) {
  const Vec3 a = normal.cwiseAbs();
  return a.x() >= a.y() ? (a.x() >= a.z() ? 0 : 2) : (a.y() >= a.z() ? 1 : 2);
}

bool coplanar_triangles_intersect(const Vec3& p1, const Vec3& q1, const Vec3& r1, const Vec3& p2, const Vec3& q2,
                                  const Vec3& r2, const Vec3& normal) {
  const int axis = dominant_axis(normal);
  const Vec2 a[3] = {project(p1, axis), project(q1, axis), project(r1, axis)};
  const Vec2 b[3] = {project(p2, axis), project(q2, axis), project(r2, axis)};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (segments_intersect_2d(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3])) return true;
  return point_in_triangle_2d(a[0], b[0], b[1], b[2]) || point_in_triangle_2d(b[0], a[0], a[1], a[2]);
}

// The decisive step of Guigue-Devillers: p1 is alone on its side of plane 2 and p2 alone on its
// side of plane 1 (both permuted so those sides are positive); the triangles meet iff the two
// intervals on the planes' intersection line overlap, which two orientation signs decide.
bool intervals_overlap(const Vec3& p1, const Vec3& q1, const Vec3& r1, const Vec3& p2, const Vec3& q2, const Vec3& r2) {
  if ((q2 - q1).dot((p2 - q1).cross(p1 - q1)) > 0.0) return false;
  if ((r2 - p1).dot((p2 - p1).cross(r1 - p1)) > 0.0) return false;
  return true;
}

// Brings triangle 2 into the canonical form (p2 alone on the positive side of plane 1), given
// triangle 1 already canonical with respect to plane 2.
bool canonical_second(const Vec3& p1, const Vec3& q1, const Vec3& r1, const Vec3& p2, const Vec3& q2, const Vec3& r2,
                      double dp2, double dq2, double dr2, const Vec3& normal1) {
  if (dp2 > 0.0) {
    if (dq2 > 0.0) return intervals_overlap(p1, r1, q1, r2, p2, q2);
    if (dr2 > 0.0) return intervals_overlap(p1, r1, q1, q2, r2, p2);
    return intervals_overlap(p1, q1, r1, p2, q2, r2);
  }
  if (dp2 < 0.0) {
    if (dq2 < 0.0) return intervals_overlap(p1, q1, r1, r2, p2, q2);
    if (dr2 < 0.0) return intervals_overlap(p1, q1, r1, q2, r2, p2);
    return intervals_overlap(p1, r1, q1, p2, q2, r2);
  }
  if (dq2 < 0.0) {
    if (dr2 >= 0.0) return intervals_overlap(p1, r1, q1, q2, r2, p2);
    return intervals_overlap(p1, q1, r1, p2, q2, r2);
  }
  if (dq2 > 0.0) {
    if (dr2 > 0.0) return intervals_overlap(p1, r1, q1, p2, q2, r2);
    return intervals_overlap(p1, q1, r1, q2, r2, p2);
  }
  if (dr2 > 0.0) return intervals_overlap(p1, q1, r1, r2, p2, q2);
  if (dr2 < 0.0) return intervals_overlap(p1, r1, q1, r2, p2, q2);
  return coplanar_triangles_intersect(p1, q1, r1, p2, q2, r2, normal1);
}

bool orientation_test(const Vec3& p1, const Vec3& q1, const Vec3& r1, const Vec3& p2, const Vec3& q2, const Vec3& r2);

}  // namespace

bool triangles_intersect(const Vec3& p1, const Vec3& q1, const Vec3& r1, const Vec3& p2, const Vec3& q2, const Vec3& r2) {
  if (!orientation_test(p1, q1, r1, p2, q2, r2)) return false;
  // The orientation test decides signs of determinants in doubles; where a corner of one lies
  // exactly in the other's plane (contoured cavities put many corners on one grid plane) those
  // signs can be rounding and report a contact between triangles a visible distance apart. Two
  // closed triangles meet only where an edge of one meets the other: the pair counts when one of
  // the six edge tests agrees, or when they are closer than rounding anyway.
  const Vec3 first[3] = {p1, q1, r1}, second[3] = {p2, q2, r2};
  for (int e = 0; e < 3; ++e) {
    if (segment_intersects_triangle(first[e], first[(e + 1) % 3], p2, q2, r2)) return true;
    if (segment_intersects_triangle(second[e], second[(e + 1) % 3], p1, q1, r1)) return true;
  }
  double size = 0.0, nearest = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) size = std::max(size, (first[a] - second[b]).norm());
  for (int a = 0; a < 3; ++a) {
    nearest = std::min(nearest, (closest_point_on_triangle(first[a], p2, q2, r2) - first[a]).norm());
    nearest = std::min(nearest, (closest_point_on_triangle(second[a], p1, q1, r1) - second[a]).norm());
  }
  return nearest <= 1e-12 * size;
}

namespace {

bool orientation_test(const Vec3& p1, const Vec3& q1, const Vec3& r1, const Vec3& p2, const Vec3& q2, const Vec3& r2) {
  const Vec3 normal2 = (p2 - r2).cross(q2 - r2);
  // A zero-area triangle (three collinear corners: CAD slivers, issue 13) has no plane: every
  // distance to it would be 0 and the pair would be decided in a 2-D projection that ignores how
  // far apart the triangles are. It is the union of its edges, so test those as segments.
  const Vec3 normal1_check = (q1 - p1).cross(r1 - p1);
  if (normal2.isZero(0.0) && !normal1_check.isZero(0.0))
    return segment_intersects_triangle(p2, q2, p1, q1, r1) || segment_intersects_triangle(q2, r2, p1, q1, r1) ||
           segment_intersects_triangle(r2, p2, p1, q1, r1);
  if (normal1_check.isZero(0.0) && !normal2.isZero(0.0))
    return segment_intersects_triangle(p1, q1, p2, q2, r2) || segment_intersects_triangle(q1, r1, p2, q2, r2) ||
           segment_intersects_triangle(r1, p1, p2, q2, r2);
  const double dp1 = (p1 - r2).dot(normal2), dq1 = (q1 - r2).dot(normal2), dr1 = (r1 - r2).dot(normal2);
  if (dp1 * dq1 > 0.0 && dp1 * dr1 > 0.0) return false;
  const Vec3 normal1 = (q1 - p1).cross(r1 - p1);
  const double dp2 = (p2 - r1).dot(normal1), dq2 = (q2 - r1).dot(normal1), dr2 = (r2 - r1).dot(normal1);
  if (dp2 * dq2 > 0.0 && dp2 * dr2 > 0.0) return false;
  // Permute triangle 1 so p1 is alone on its side of plane 2, flipping triangle 2's orientation
  // (q2 <-> r2) when that side is the negative one.
  if (dp1 > 0.0) {
    if (dq1 > 0.0) return canonical_second(r1, p1, q1, p2, r2, q2, dp2, dr2, dq2, normal1);
    if (dr1 > 0.0) return canonical_second(q1, r1, p1, p2, r2, q2, dp2, dr2, dq2, normal1);
    return canonical_second(p1, q1, r1, p2, q2, r2, dp2, dq2, dr2, normal1);
  }
  if (dp1 < 0.0) {
    if (dq1 < 0.0) return canonical_second(r1, p1, q1, p2, q2, r2, dp2, dq2, dr2, normal1);
    if (dr1 < 0.0) return canonical_second(q1, r1, p1, p2, q2, r2, dp2, dq2, dr2, normal1);
    return canonical_second(p1, q1, r1, p2, r2, q2, dp2, dr2, dq2, normal1);
  }
  if (dq1 < 0.0) {
    if (dr1 >= 0.0) return canonical_second(q1, r1, p1, p2, r2, q2, dp2, dr2, dq2, normal1);
    return canonical_second(p1, q1, r1, p2, q2, r2, dp2, dq2, dr2, normal1);
  }
  if (dq1 > 0.0) {
    if (dr1 > 0.0) return canonical_second(p1, q1, r1, p2, r2, q2, dp2, dr2, dq2, normal1);
    return canonical_second(q1, r1, p1, p2, q2, r2, dp2, dq2, dr2, normal1);
  }
  if (dr1 > 0.0) return canonical_second(r1, p1, q1, p2, q2, r2, dp2, dq2, dr2, normal1);
  if (dr1 < 0.0) return canonical_second(r1, p1, q1, p2, r2, q2, dp2, dr2, dq2, normal1);
  return coplanar_triangles_intersect(p1, q1, r1, p2, q2, r2, normal1);
}

}  // namespace

bool segment_intersects_triangle(const Vec3& a, const Vec3& b, const Vec3& p, const Vec3& q, const Vec3& r) {
  const Vec3 normal = (q - p).cross(r - p);
  const double da = (a - p).dot(normal), db = (b - p).dot(normal);
  // A segment lying in the triangle's plane in exact arithmetic (for example an edge of the next
  // ring of a cone, collinear with the pole) comes out with distances of rounding size and
  // random signs; the orientation test below is meaningless then. Within a relative 1e-12 the
  // segment counts as coplanar and is decided in 2-D. Compared squared: most calls (neighbouring
  // faces of a fine mesh) end at the next line, and they need no square root.
  const double size_squared =
      std::max({(a - p).squaredNorm(), (b - p).squaredNorm(), (q - p).squaredNorm(), (r - p).squaredNorm()});
  const double on_plane_squared = 1e-24 * normal.squaredNorm() * size_squared;
  const bool a_on = da * da <= on_plane_squared, b_on = db * db <= on_plane_squared;
  if (!a_on && !b_on && ((da > 0.0 && db > 0.0) || (da < 0.0 && db < 0.0))) return false;
  const double size = std::sqrt(size_squared);
  // Where both ends lie within 1e-6 of the segment's length from the plane (coplanar cavity
  // triangles along a flat wall), signs across the plane are rounding: decide in 2-D as well.
  const bool nearly_in_plane = std::max(std::fabs(da), std::fabs(db)) < 1e-6 * normal.norm() * (b - a).norm();
  if ((a_on && b_on) || nearly_in_plane) {
    const int axis = dominant_axis(normal);
    const Vec2 a2 = project(a, axis), b2 = project(b, axis);
    const Vec2 t[3] = {project(p, axis), project(q, axis), project(r, axis)};
    for (int j = 0; j < 3; ++j)
      if (segments_intersect_2d(a2, b2, t[j], t[(j + 1) % 3])) return true;
    return point_in_triangle_2d(a2, t[0], t[1], t[2]);
  }
  // The segment crosses (or touches) the plane: the crossing point is inside the closed
  // triangle iff the three tetrahedra (a, b, edge) have consistent orientation.
  const Vec3 ab = b - a;
  const double s1 = ab.dot((q - a).cross(p - a));
  const double s2 = ab.dot((r - a).cross(q - a));
  const double s3 = ab.dot((p - a).cross(r - a));
  const bool has_negative = s1 < 0 || s2 < 0 || s3 < 0;
  const bool has_positive = s1 > 0 || s2 > 0 || s3 > 0;
  if (has_negative && has_positive) return false;
  // The signs above are rounding where the crossing point is near an edge of the triangle or the
  // segment's end is near its plane (grid-aligned corners of a contoured cavity): construct the
  // crossing point and measure. Where the segment is steep enough for that point to be accurate
  // (sine of the angle to the plane >= 1e-6) a point clearly off the triangle is no contact.
  const double across = std::fabs(da - db);
  if (across >= 1e-6 * normal.norm() * ab.norm() && across > 0.0) {
    const Vec3 crossing = a + (da / (da - db)) * ab;
    if ((closest_point_on_triangle(crossing, p, q, r) - crossing).norm() > 1e-9 * size) return false;
  }
  return true;
}

}  // namespace offsetopt
