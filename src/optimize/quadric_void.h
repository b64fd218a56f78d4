// The quadric void (docs/design.md "Reachability", use 2): where the offset model misses a goal that
// some void reaches, or reaches it well short of the best any void does, the void written is the
// reachability programme's optimum, {q < 0} ∩ carvable (cavity/reachability.h), contoured like any
// cavity, φ = min(d_out − wall − c·h, −q/|∇q|) (cavity/contour_cavity.h), and corrected in moment
// space until the written solid verifies.
//
// The correction moves the quadric, not the programme: the programme's duals, hence its quadric,
// jump between bases when its data move a little (a floating buoy's contour flipped between two
// voids 9% apart, round after round), while the contour's integrals I move smoothly with q's ten
// coefficients c. Where the boundary follows the quadric it moves by −δq/|∇q| along the normal, so
//   ∂I_k/∂c_j = −∫_{∂void ∩ {q = 0}} m_k m_j / |∇q| dA        (one point per face),
// and each round takes the least-norm step δc that brings the goal's violated rows (shape/goal.h,
// evaluated on the written integrals with `headroom` of the user's margins inside them) to zero
// to first order, divided by the gain the last such step showed, or steps back towards the best
// round when a round did not halve its violation (optimize/quadric_correction.h: on thin voids
// that first order misses half of what moves). All of it in the normalised frame (origin,
// 1 / diagonal), where the ten coefficients are of one scale.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "cavity/contour_cavity.h"
#include "cavity/reachability.h"
#include "cavity/verify_offsets.h"
#include "geometry/bvh.h"
#include "mesh/mesh.h"
#include "optimize/offset_optimization.h"

namespace offsetopt {

struct QuadricVoidInput {
  const Mesh* outer = nullptr;            // the outer surface (the input: no outer offsets)
  const TriangleBvh* outer_bvh = nullptr;
  Quadric start;                          // the programme's optimum (Reachability::optimum)
  // The programme it came from (its cells and occupancy), optional: the start is moved by a
  // constant so that its void holds the occupancy's volume on those cells (see the .cpp).
  const Reachability* programme = nullptr;
  GoalSpec goal_in_frame;                 // the goal in the normalised frame, the user's margins
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // of the normalised frame, input units
  double diagonal = 1.0;                  // its scale is 1 / diagonal
  ContourCavityOptions contour;
  VerifyInput verify;                     // outer, goal, tolerances, precision; inner is set per round
  int max_rounds = 6;                     // corrections after the first contour
  double headroom = 0.01;                 // fraction of the user's margins aimed inside them
};

struct QuadricVoid {
  // The last contour and the outer surface as they read back from the files (rounded to
  // verify.precision, cavity/round_for_output.h); empty when no contour was made.
  Mesh outer, written;
  Verification verification;              // of the last contour
  std::vector<ContourRound> rounds;
  Quadric quadric;                        // of the last round, input units
  std::string message;                    // why it stopped short, when it did
};

QuadricVoid write_quadric_void(const QuadricVoidInput& input);

}  // namespace offsetopt
