// Exact contact tests between closed triangles and segments, the semantics of CGAL's
// do_intersect on a kernel with exact predicates (Epick): every decision is the sign of an
// orient3d or orient2d determinant of input coordinates (geometry/convex_hull_3d.h and
// convex_hull_2d.h: a floating-point filter, then exact expansions), never a tolerance and never
// a constructed point. Touching counts: a corner on the other triangle's edge, an edge through
// its interior, coplanar triangles sharing only a boundary point all meet. Exact for finite
// coordinates below ~1e100 in magnitude.
//
// Coplanar cases are decided in the projection that drops one coordinate axis, chosen where the
// triangle's projection has non-zero exact area: there, 2-D orientations of points of the plane
// have the same signs as in the plane, so the projection loses nothing.
#pragma once
#include <Eigen/Core>

namespace offsetopt {

// Signs of orient3d (geometry/convex_hull_3d.h: > 0 when d is on the side (b − a) × (c − a)
// points to) and orient2d, exact, with a second filter in extended precision between the
// floating-point one and the exact expansions: surfaces with flat regions (a contoured cavity
// under a CAD face) put many corners within rounding of one plane, where the first filter
// cannot decide and the expansions would be the bulk of a search.
int orient3d_sign(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, const Eigen::Vector3d& d);
int orient2d_sign(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c);

// The three points lie on one line (two equal points included): the triangle has no plane.
// CGAL's self-intersection search reports such a face by itself and tests it against nothing.
bool collinear_exact(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r);

// orient3d_sign(a, b, c, ·) for many points against one triangle's plane: (b − a) × (c − a) and
// its part of the filter's error bound are computed once; what the filter leaves open goes to
// orient3d_sign's exact stages, so every sign is the same.
class PlaneSide {
 public:
  PlaneSide(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);
  int operator()(const Eigen::Vector3d& d) const;

 private:
  const Eigen::Vector3d &a_, &b_, &c_;
  Eigen::Vector3d normal_, bound_;  // bound_: per component, |the two products| it is the difference of
};

// Closed segment a-b (a != b) against the closed triangle p-q-r (not collinear).
bool segment_meets_triangle_exact(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& p,
                                  const Eigen::Vector3d& q, const Eigen::Vector3d& r);

// The same with the ends' sides of the triangle's plane known (orient3d_sign(p, q, r, a) and
// (p, q, r, b)).
bool segment_meets_triangle_exact(const Eigen::Vector3d& a, const Eigen::Vector3d& b, int side_a, int side_b,
                                  const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r);

// Triangles v-f1-f2 and v-g1-g2 (neither collinear) lying in one plane and sharing the corner v:
// whether the edge f1-f2 meets the closed triangle g or the edge g1-g2 meets f (the rule for
// faces on a common vertex, geometry/faces_intersect_exact.h). The same answer as the two
// segment_meets_triangle_exact tests, from 6 orient2d signs in one projection (whether the
// faces' wedges at v share a ray) instead of ~40: the faces of a flat region meet their
// coplanar neighbours this way by the thousand.
bool coplanar_fan_pair_meets(const Eigen::Vector3d& v, const Eigen::Vector3d& f1, const Eigen::Vector3d& f2,
                             const Eigen::Vector3d& g1, const Eigen::Vector3d& g2);

// Closed triangles a and b (neither collinear) share at least one point.
bool triangles_meet_exact(const Eigen::Vector3d a[3], const Eigen::Vector3d b[3]);

}  // namespace offsetopt
