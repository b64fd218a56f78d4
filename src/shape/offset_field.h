// Offset directions and bounds from a contracted mesh (Musialski et al. 2015, section 4: inner
// vectors toward the meso-skeleton, 4.2: maximal and minimal bounds; docs/design.md "Meso-skeleton and
// offset field"). All lengths are in the units of `mesh`.
//
// For input vertex x_i with contracted position s_i (same index) and outward unit normal n_i
// (area-weighted, geometry/vertex_normals.h), each vertex gets one source:
//   contraction  v_i = (s_i - x_i)/|s_i - x_i|, usable when |s_i - x_i| > min_length * diagonal,
//                -v_i . n_i >= min_inward_cosine and v_i enters the solid at x_i
//                (geometry/vertex_cone.h); delta_u_i = |s_i - x_i|.
//   shortened    as contraction, but the ray x_i + t v_i leaves the solid (first hit of a face
//                not incident to x_i, through the BVH) at t_exit < |s_i - x_i|:
//                delta_u_i = exit_fraction * t_exit.
//   shallow      a usable contraction direction whose skeleton point is shallow: under flat or
//                nearly flat regions the meso-skeleton runs close to the surface (the skeleton
//                of a flat-capped cylinder reaches the cap), the directions converge on it
//                within a few per cent of the part's radius and would leave a thick part with
//                a bound far below any wall thickness. When the skeleton point's depth
//                |s_i - x_i| (-v_i . n_i) is below shallow_fraction * rho_i, rho_i the radius of
//                the largest inscribed ball touching x_i (estimated from above by 25 rays,
//                geometry/inscribed_ball.h, and only when the depth is below shallow_fraction
//                times half the chord along -n_i, an upper bound of rho_i), the vertex
//                uses v_i = -n_i (parallel directions cannot cross) and
//                delta_u_i = min(exit_fraction * chord along -n_i, rho_i).
//   fallback     the contraction direction is unusable: v_i = -n_i and
//                delta_u_i = exit_fraction * (distance along -n_i to the first face hit): with
//                the default 1/2 the vertex travels at most to the middle of the part, where the
//                opposite side's vertices stop too.
//   immobile     as fallback, but -n_i does not enter the solid, the ray hits nothing (an open
//                mesh) or the normal is undefined: delta_u_i = 0 (v_i = -n_i, or 0 without a
//                normal).
// fallback_count counts every vertex moving along -n_i (shallow + fallback + immobile).
// Minimal inner offset for a wall thickness t measured along the normal (paper 4.2):
//   delta_l_i = t / max(c, -v_i . n_i),  c = thickness_cosine_floor (default 0.2: an oblique
//   direction never demands more than 5 t).
// No clamping of delta_l to delta_u happens here: where a part is thinner than the wall the band
// is empty (delta_l > delta_u) and the optimiser decides (docs/design.md, "Reduced problem").
// Outer directions: w_i = -v_i (default, the paper's choice) or n_i.
#pragma once
#include <cstdint>
#include <vector>

#include "geometry/bvh.h"
#include "mesh/mesh.h"

namespace offsetopt {

enum class OuterDirections { reversed_inner, normal };

struct OffsetFieldOptions {
  double wall = 0.0;                    // t >= 0, mesh units
  double thickness_cosine_floor = 0.2;  // c in (0, 1]
  double min_inward_cosine = 0.2;       // contraction direction unusable when -v.n is below this; in [0, 1)
  double exit_fraction = 0.5;           // in (0, 1]
  double min_length = 1e-9;             // fraction of the bounding-box diagonal; >= 0
  double shallow_fraction = 0.5;        // in [0, 1]; 0 turns the shallow test off
  OuterDirections outer = OuterDirections::reversed_inner;
  int threads = 2;                      // >= 1; vertices split in fixed ranges, every result identical for any count

  // Empty when the options are valid, else the first out-of-range field (offset_field throws
  // std::invalid_argument with it).
  std::string check() const;
};

enum class OffsetSource : std::uint8_t { contraction = 0, shortened = 1, shallow = 2, fallback = 3, immobile = 4 };

struct OffsetField {
  Vertices inner;           // v, #V by 3, unit (zero only for an immobile vertex without normal)
  Vertices outer;           // w, #V by 3
  Vertices normals;         // n, #V by 3, outward unit (zero when undefined)
  Eigen::VectorXd lower;    // delta_l, #V
  Eigen::VectorXd upper;    // delta_u, #V, >= 0
  std::vector<OffsetSource> source;  // #V
  int shortened_count = 0;
  int shallow_count = 0;
  int fallback_count = 0;   // shallow + fallback + immobile: every vertex moving along -n
  int immobile_count = 0;
};

// `bvh` must index `mesh` (the same V and F); `contracted` is #V by 3 (laplacian_contraction's V).
OffsetField offset_field(const Mesh& mesh, const Vertices& contracted, const TriangleBvh& bvh,
                         const OffsetFieldOptions& options = {});

}  // namespace offsetopt
