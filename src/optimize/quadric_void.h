// The quadric void (DESIGN.md "Reachability", use 2): where the offset model misses a goal that
// some void reaches, or reaches it well short of the best any void does, the void written is the
// reachability programme's optimum, {q < 0} ∩ carvable (cavity/reachability.h), contoured like any
// cavity, φ = min(d_out − wall − c·h, −q/|∇q|) (cavity/contour_cavity.h), and corrected in moment
// space: the programme is solved again with the difference the contour made,
//   Δ = integrals(contour) − integrals(occupancy),
// read as void beyond the occupancy (ReachabilityOptions::void_shift), until the written solid
// verifies or the rounds run out. Each programme aims `headroom` of the user's margins inside them,
// as the offset model's corrections do, since the next contour's moments differ by a little noise.
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
  const Reachability* reach = nullptr;    // reachable, with its cells
  VolumeIntegrals outer_integrals;        // of *outer, any origin
  GoalSpec goal;                          // input units, the user's margins
  double ground_z = 0.0;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // the one `reach` was computed about
  double diagonal = 1.0;
  ReachabilityOptions reach_options;      // as for `reach`
  ContourCavityOptions contour;
  VerifyInput verify;                     // outer, goal, tolerances; inner is set per round
  int max_rounds = 6;                     // corrections after the first contour
  double headroom = 0.01;                 // fraction of the user's margins aimed inside them
};

struct QuadricVoid {
  bool attempted = false;
  Mesh written;                           // the last contour (empty when none was made)
  Verification verification;              // of the last contour
  std::vector<ContourRound> rounds;
  std::optional<Quadric> quadric;         // of the last round
  std::string message;                    // why no contour was written, when none was
};

QuadricVoid write_quadric_void(const QuadricVoidInput& input);

}  // namespace offsetopt
