// Ray-triangle intersection (Moller & Trumbore 1997, "Fast, Minimum Storage Ray/Triangle
// Intersection"). The ray is origin + t * direction (direction need not be unit; t is in units
// of |direction|). Barycentric coordinates (u, v) are those of b and c: the hit point is
// (1 - u - v) a + u b + v c. Triangles are oriented counter-clockwise seen from outside, so
// direction . ((b - a) x (c - a)) > 0 means the ray leaves the solid there.
#pragma once
#include <Eigen/Core>

namespace offsetopt {

struct RayTriangleHit {
  bool hit = false;         // the line meets the (tolerance-enlarged) triangle; t may be any sign
  double t = 0.0;           // ray parameter of the hit
  double u = 0.0, v = 0.0;  // barycentrics of b and c
  double orientation = 0.0;  // direction . (b - a) x (c - a): > 0 exiting, < 0 entering, 0 parallel
  // The hit is within `tolerance` of an edge or vertex (in barycentric units), or the ray is
  // (nearly) parallel to the plane: a parity count must not trust it.
  bool ambiguous = false;
};

// `tolerance` enlarges the triangle by that much in barycentric units (a hit with
// u, v, 1 - u - v >= -tolerance counts), so a ray through a shared edge is never lost between
// its two triangles; such hits are flagged ambiguous. A ray parallel to the plane (|sine| below
// 1e-12) never hits; it is flagged ambiguous when it lies in the plane (within 1e-9 of the
// longest edge).
RayTriangleHit ray_triangle(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                            const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                            double tolerance = 1e-10);

}  // namespace offsetopt
