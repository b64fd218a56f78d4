// The whole optimisation of DESIGN.md's pipeline for one input mesh (Musialski et al. 2015):
//   frame (ground, support) -> contraction meso-skeleton -> offset directions and bounds
//   -> manifold-harmonic basis Γk -> reduced problem in α (and β with outer offsets),
//      solved by the augmented Lagrangian + L-BFGS-B -> final surfaces -> verification.
// Everything is computed in a normalised frame (ground contact centroid at the origin, z from the
// ground, bounding-box diagonal 1) and reported back in input units. The input is never moved.
#pragma once
#include <string>
#include <vector>

#include "io/json.h"
#include "mesh/mesh.h"
#include "optim/augmented_lagrangian.h"
#include "shape/fix_region.h"
#include "shape/goal.h"
#include "shape/reduced_problem.h"
#include "spectral/manifold_harmonics.h"

namespace offsetopt {

// Which cavity is written (DESIGN.md "The written cavity"): the smooth inner offset surface
// (the paper's result, the input's connectivity), the contour of the implicit cavity
// (shape/contour_cavity.h, corrected in moment space), or the offset surface when it verifies as
// it is and the contour otherwise.
enum class CavityMode { automatic, offset, contour };
const char* to_string(CavityMode mode);
bool parse_cavity_mode(const std::string& text, CavityMode& mode);

struct OptimizeSettings {
  GoalKind goal = GoalKind::stand;
  int k = 36;                    // basis size; 0 means every vertex (`--k all`, paper eq. 1)
  BasisKind basis = BasisKind::mass;
  BoundsMode bounds = BoundsMode::clamp;
  bool outer = false;
  // Lengths in input units; a negative value means "the default", a fraction of the diagonal:
  double wall = -1.0;            // 0.01 x diagonal
  double outer_max = -1.0;       // 0.02 x diagonal
  double margin = -1.0;          // 0.002 x diagonal (stand: inside the support polygon; roly-poly
                                 // and float: the safeguard ε below the centre)
  double ground_tol = -1.0;      // 0.001 x diagonal
  double radius = -1.0;          // roly-poly: hemisphere radius; default: sphere fitted to the bottom
  double penalty = 1.0;          // wp on the outer DC coefficient
  double fill_density = 1.0;     // stand-filled
  double fluid_density = -1.0;   // float: required, in (0, 1)
  double target_volume = -1.0;   // volume: required, input units cubed
  FixRegion fix;
  double gap = 0.05;             // s: inner offsets stop at (1 - s) of the skeleton distance
  double ramp = 2e-3;            // τ of the smooth clamp, fraction of the diagonal
  double start_fraction = 0.5;   // start inside the band (see ReducedOptions)
  CavityMode cavity = CavityMode::automatic;
  // The contoured cavity: grid spacing wall / cavity_cells_per_wall, interpolation margin
  // cavity_margin_cells · h (shape/contour_cavity.h); at most max_correction_rounds solves again
  // with the contour's moments.
  double cavity_cells_per_wall = 1.5;
  double cavity_margin_cells = 0.25;
  int max_correction_rounds = 6;
  // `--cavity offset` only: after a solve, vertices on folds of the inner surface get their upper
  // bound multiplied by repair_shrink and vertices on walls thinner than half the requested one
  // their lower bound raised by half the wall; then the problem is solved again, at most
  // max_repair_rounds times.
  int max_repair_rounds = 8;
  // The upper bound is lowered to rise at most this much per unit of surface distance, so
  // neighbouring vertices cannot stop at very different depths (a fold).
  double bound_slope = 0.5;
  double repair_shrink = 0.6;
  bool repair_ring = true;  // also tighten the one-ring of every vertex on a fold
  double warm_penalty_cap = 1e3;  // a repair round starts from min(last penalty, this)
  // Tolerances and caps of the augmented Lagrangian. The goal's constraints are met to 1e-8 of
  // the diagonal (the margins carry 1e-7 extra, so the user's margin holds exactly); stationarity
  // to 1e-4, scaled (the objective is a preference, not a requirement: on the demo meshes 1e-6
  // changes it in the 7th digit and costs 1.5 to 3 times the evaluations); at most 2000
  // evaluations per solve (each is O(#F + 10·#V·k)), so every round of the solve is capped.
  AlOptions solver = default_solver_params();
  // Report every outer iteration of the solver through the progress callback (`-v`).
  bool trace_solver = false;
  // Threads per stage (1..64). With more than one, the basis is computed alongside the skeleton
  // and every stage cuts its work into fixed parts; with one, everything runs on the calling
  // thread, one stage after another (the lowest peak memory). The output is bit for bit the same
  // for any count.
  int threads = 2;

  static AlOptions default_solver_params() {
    AlOptions p;
    p.feasibility_tolerance = 1e-8;
    p.stationarity_tolerance = 1e-4;
    p.complementarity_tolerance = 1e-4;
    p.max_outer_iterations = 30;
    p.max_evaluations = 2000;
    // A violation above 1e-4 of the diagonal that stagnates once triggers the least-violation
    // check: a goal no carving can reach (the horse cannot stand: 1344 evaluations before, 454
    // after) is found before the penalty reaches 1e5, where each subproblem costs hundreds of
    // evaluations. Near the tolerance stagnation is often noise, and the default patience holds.
    p.clear_violation_factor = 1e4;
    return p;
  }
  static OptimizeSettings defaults() { return OptimizeSettings(); }
};

// Empty when the settings are valid, else a message naming the option.
std::string check_optimize_settings(const OptimizeSettings& settings);

enum class OptimizeStatus {
  verified,       // goal met and the solid is valid
  goal_not_met,   // ran; the result misses the goal or is invalid (see the report)
  bad_input,      // the mesh or settings do not allow the goal (message says why)
};

struct OptimizeResult {
  OptimizeStatus status = OptimizeStatus::bad_input;
  std::string message;          // one line: why it failed (empty when verified)
  Mesh inner, outer, printable, skeleton;  // input units
  Json report;                  // the full report (see README), without timings
  Json timings;                 // per-stage seconds (not reproducible; kept apart)
  std::vector<std::string> warnings;
};

OptimizeResult optimize_offsets(const Mesh& input, const OptimizeSettings& settings,
                                const std::function<void(const std::string&)>& progress = {});

}  // namespace offsetopt
