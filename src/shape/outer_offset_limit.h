// How far each vertex of a closed surface may be thickened along its outer direction without the
// thickened surface folding onto itself (docs/design.md "Reduced problem": the outer offsets; issue 20).
// All lengths in the units of `mesh`; directions w_i unit (or zero), pointing out of the solid;
// n_i the outward vertex normals (geometry/vertex_normals.h). Three rules lower the requested
// limit r_i, then a slope bound joins them:
//   free      the ray x_i + t w_i (faces around x_i ignored) first meets the surface at t_hit:
//             limit_i <= free_fraction * t_hit, so two parts facing each other each take at most
//             their share of the gap between them;
//   focal     for every face around x_i, the constant offset delta (either sign) at which the
//             face, its corners moved by delta w, turns over (its normal reverses: the roots of
//             the quadratic N(delta) . N(0) = 0): limit_i <= focal_fraction * the smallest |root|.
//             This is the direction field's own crossing distance (directions converging in a
//             crease, or jumping between neighbours);
//   nearest   the point p = x_i + reach * limit_i * w_i must lie in x_i's part of the outside:
//             its distance to the surface at least nearest_fraction * its distance to x_i's own
//             faces (a point beyond the outer medial axis is nearer to some other part of the
//             surface; on a flat or convex neighbourhood the own faces are at p's height above
//             the tangent plane, across a concave crease they are nearer, and the crease is not a
//             fold). Otherwise the limit is halved, at most max_halvings times, then 0. A
//             direction w_i below the tangent plane (w_i . n_i <= 0) gets 0;
// then limit = lipschitz_envelope(limit, slope) (shape/lipschitz_envelope.h): neighbouring
// limits differ by at most slope * edge length, so a clamp against them cannot step.
// A vertex with r_i = 0, a zero direction or a zero normal gets 0.
#pragma once
#include <string>

#include <Eigen/Core>

#include "geometry/bvh.h"
#include "mesh/mesh.h"

namespace offsetopt {

struct OuterOffsetLimitOptions {
  double free_fraction = 0.5;     // in (0, 1]
  double focal_fraction = 1.0;    // in (0, 1]
  double reach = 2.0;             // >= 1: the nearest rule tests this multiple of the limit
  double nearest_fraction = 0.8;  // in (0, 1]
  int max_halvings = 6;           // in [0, 30]
  double slope = 0.5;             // >= 0
  int threads = 2;                // >= 1; vertices split in fixed ranges, the same result for any count

  std::string check() const;      // empty when valid
};

struct OuterOffsetLimit {
  Eigen::VectorXd limit;          // #V, in [0, r_i]
  // Vertices whose limit each rule lowered below the request (before the slope bound).
  int free_limited = 0, focal_limited = 0, nearest_limited = 0;
};

// `bvh` indexes `mesh`; `outer_directions`, `normals` #V by 3; `requested` #V, >= 0.
// Throws std::invalid_argument on invalid options or shapes.
OuterOffsetLimit outer_offset_limit(const Mesh& mesh, const TriangleBvh& bvh, const Vertices& outer_directions,
                                    const Vertices& normals, const Eigen::VectorXd& requested,
                                    const OuterOffsetLimitOptions& options = {});

}  // namespace offsetopt
