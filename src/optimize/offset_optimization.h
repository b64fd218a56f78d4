// src/optimize (this is the folder's main header): the pipeline on top of the offset model
// (src/shape) and what is written (src/cavity), in named stages returning typed results, and the
// preview picture. It builds no JSON and prints nothing. It may include every folder below it;
// only src/cli sits above it.
//
// The whole optimisation of docs/design.md's pipeline for one input mesh (Musialski et al. 2015):
//   frame (ground, support) -> contraction meso-skeleton -> offset directions and bounds
//   -> manifold-harmonic basis Γk -> reduced problem in α (and β with outer offsets),
//      solved by the augmented Lagrangian + L-BFGS-B -> final surfaces -> verification.
// Everything is computed in a normalised frame (ground contact centroid at the origin, z from the
// ground, bounding-box diagonal 1) and reported back in input units. The input is never moved.
#pragma once
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "geometry/mesh_defects.h"
#include "mesh/mesh.h"
#include "optim/augmented_lagrangian.h"
#include "shape/fix_region.h"
#include "shape/goal.h"
#include "shape/reduced_problem.h"
#include "cavity/contour_cavity.h"
#include "cavity/open_cavity.h"
#include "cavity/verify_offsets.h"
#include "optimize/reachability_stage.h"
#include "skeleton/laplacian_contraction.h"
#include "spectral/lanczos_eigensolver.h"
#include "spectral/manifold_harmonics.h"

namespace offsetopt {

// Which cavity is written (docs/design.md "The written cavity"): the smooth inner offset surface
// (the paper's result, the input's connectivity), the contour of the implicit cavity
// (cavity/contour_cavity.h, corrected in moment space), or the offset surface when it verifies as
// it is and the contour otherwise.
// `quadric`: the reachability programme's optimal void (optimize/quadric_void.h), contoured.
enum class CavityMode { automatic, offset, contour, quadric };
const char* to_string(CavityMode mode);
bool parse_cavity_mode(const std::string& text, CavityMode& mode);

struct OptimizeOptions {
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
  // Drain holes through the contoured cavity (cavity/open_cavity.h): at given points of the void,
  // and/or one per cavity shell at its lowest point (`--drain-holes auto`); radius in input units,
  // < 0: PrusaSlicer's default drain hole, 2 (mm). Asking for one writes the contoured cavity.
  std::vector<DrainHoleRequest> drain_holes;
  bool drain_holes_auto = false;
  double drain_hole_radius = -1.0;
  bool wants_drain_holes() const { return drain_holes_auto || !drain_holes.empty(); }
  double gap = 0.05;             // s: inner offsets stop at (1 - s) of the skeleton distance
  double ramp = 2e-3;            // τ of the smooth clamp, fraction of the diagonal
  double start_fraction = 0.5;   // start inside the band (see ReducedOptions)
  // The --flatten height the input was already cut at (the CLI's pose options; 0: none), so a
  // flat-base remedy names the height to type.
  double flatten = 0.0;
  // The --up axis the input was turned by and whether --pose stable was given (the CLI's pose
  // options), so that an other-pose remedy names what to type for the file (reachability_stage.h).
  std::string up = "+z";
  bool posed_stable = false;
  CavityMode cavity = CavityMode::automatic;
  // `auto` tries the quadric void when the offset void misses a goal some void reaches, or when
  // it achieves less than this fraction of the possible lowering (Optimality); the offset void is
  // kept when its objective is within quadric_tie of the quadric void's (walls that follow the
  // shape are worth a little). At 0.95 the demo goals, whose offset voids reach 0.98, pay no second
  // contour; real meshes, at 0.68 to 0.91, get the quadric void.
  double quadric_below_fraction = 0.95;
  // When the offset model's own integrals (before any contour) predict less than this fraction of
  // the possible lowering, the quadric void is made first and the offset void contoured only if
  // the quadric void does not verify (a contour reaches less than its model predicts).
  double quadric_first_below = 0.95;
  double quadric_tie = 0.01;
  // The contoured cavity: grid spacing wall / cavity_cells_per_wall, the wall-bound part at
  // wall + cavity_margin_cells · h (0: at the requested wall; cavity/contour_cavity.h); at most
  // max_correction_rounds solves again with the contour's moments.
  double cavity_cells_per_wall = 1.5;
  double cavity_margin_cells = 0.0;
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
  // Observer for a progress display: a stage ("basis", "reachability", "skeleton", "solve",
  // "verify", "contour") and its fraction done, in [0, 1] (1: finished), or -1 when unknown. The
  // basis reports from its own thread, alongside the others, so the observer must be safe to call
  // from two threads. It is never read back: no output depends on it.
  std::function<void(const std::string& stage, double fraction)> on_stage_progress;
  // Threads per stage (1..64). With more than one, the basis is computed alongside the skeleton
  // and every stage cuts its work into fixed parts; with one, everything runs on the calling
  // thread, one stage after another (the lowest peak memory). The output is bit for bit the same
  // for any count.
  int threads = 2;
  // The coarsest precision of the mesh files to be written (meshio/write_mesh.h, stored_precision
  // of -o, --inner, --outer-mesh): float32 when any is STL. The surfaces are rounded to it before
  // the final verification (cavity/round_for_output.h), so what is verified is what reads back,
  // and the contour keeps the rounding's margin on top of the wall.
  StoredPrecision output_precision = StoredPrecision::exact;
  // The input's self-intersections as the input boundary found them (meshio/load_input.h), when
  // the mesh given to optimize_offsets is that mesh as loaded; unset: searched here (the report's
  // before.self_intersections).
  std::optional<SelfIntersectionReport> input_self_intersections;

  static AlOptions default_solver_params() {
    AlOptions p;
    p.feasibility_tolerance = 1e-8;
    p.stationarity_tolerance = 1e-4;
    p.complementarity_tolerance = 1e-4;
    p.max_outer_iterations = 30;
    p.max_evaluations = 2000;
    // The first subproblem's penalty: the solver's own choice is 10 on the demo goals (their
    // normalised objectives are below 1), and the first inner solve then wanders far from the
    // constraints. 100: the census standing (empty or filled) the same, its roly-poly 31% and the
    // six demo goals 15% fewer evaluations (docs/solver.md "The first penalty").
    p.initial_penalty = 100;
    // A violation above 1e-4 of the diagonal that stagnates once triggers the least-violation
    // check: a goal no carving can reach (the horse cannot stand: 1344 evaluations before, 454
    // after) is found before the penalty reaches 1e5, where each subproblem costs hundreds of
    // evaluations. Near the tolerance stagnation is often noise, and the default patience holds.
    p.clear_violation_factor = 1e4;
    return p;
  }
  static OptimizeOptions defaults() { return OptimizeOptions(); }

  // Empty when the options are valid, else a message naming the option.
  std::string check() const;
};

enum class OptimizeStatus {
  verified,       // goal met and the solid is valid
  goal_not_met,   // ran; the result misses the goal or is invalid (see the report)
  bad_input,      // the mesh or options do not allow the goal (message says why)
};

// What a run found, stage by stage, as plain values (cli/optimize_report.h writes them as the
// JSON report). Input units unless a name says otherwise.

// The goal as set up on the input (roly-poly: the sphere; spin: the tip).
struct GoalSetup {
  GoalKind kind = GoalKind::stand;
  std::optional<Eigen::Vector3d> sphere_center;  // roly-poly
  double sphere_radius = 0.0;                    // roly-poly
  std::optional<Eigen::Vector3d> tip;            // spin
};

// The normalised frame and the lengths the options resolved to (a default is a fraction of the
// diagonal).
struct FrameSummary {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // the ground contact centroid, on the ground
  double scale = 1.0;                                 // 1 / diagonal
  double diagonal = 1.0;
  double wall = 0.0, outer_max = 0.0, margin = 0.0, ground_tol = 0.0;
};

// The meso-skeleton and the offset field (vertex counts). A part left solid is one thinner than
// two walls: its band is empty (the wall's lower bound at or above the skeleton's upper one), so it
// keeps no cavity.
struct OuterLimitSummary {
  int free_limited = 0, focal_limited = 0, nearest_limited = 0;
  double mean_fraction = 0.0;
  int fold_repairs = 0;             // solves repeated with limits lowered where the surface still folded
};

struct FieldSummary {
  int contraction_steps = 0;
  ContractionStatus contraction_status = ContractionStatus::step_cap;
  double volume_ratio = 1.0;
  int shortened = 0;                // upper bounds shortened where the segment leaves the solid
  int fallback = 0;                 // moving along the inward normal
  int fixed = 0;                    // in the --fix region
  int left_solid_vertices = 0;      // in parts left solid, before repairs
  int left_solid_vertices_after_repairs = 0;
  int clamped_at_wall = 0;          // final inner offsets within a ramp of the wall ...
  int clamped_at_skeleton = 0;      // ... or of the skeleton
  // With --outer (shape/outer_offset_limit.h): vertices whose outer limit each rule lowered below
  // --outer-max, and the mean limit over the vertices away from the ground, as a fraction of it.
  std::optional<OuterLimitSummary> outer_limit;
};

struct BasisSummary {
  bool identity = false;            // --k all: one variable per vertex, no eigensolver
  BasisKind kind = BasisKind::mass;
  int k = 0;                        // columns (the vertex count with identity)
  // The eigensolver's status and largest eigenvalue; absent with identity.
  std::optional<LanczosStatus> status;
  double largest_eigenvalue = 0.0;
};

// One `--cavity offset` repair round: the vertices whose bounds were tightened.
struct RepairRound {
  long long intersecting_vertices = 0;
  long long thin_wall_vertices = 0;
};

// One of the goal's constraints at the end of the solve, normalised frame.
struct ConstraintValue {
  std::string name;
  bool equality = true;             // "= 0", else "<= 0"
  double value = 0.0;
};

struct SolverSummary {
  AlStatus status = AlStatus::invalid_input;
  double objective = 0.0;
  int outer_iterations = 0, inner_iterations = 0;  // of the last solve
  int evaluations = 0;              // over every solve
  int repair_rounds = 0;
  std::vector<RepairRound> repairs;
  double max_violation = 0.0;       // of the last solve, normalised frame
  int variables = 0;
  std::vector<ConstraintValue> constraints;  // equalities, then inequalities
};

// The input as it came.
struct InputSummary {
  Vector10d properties = Vector10d::Zero();  // [m, cx, cy, cz, Ixx, Iyy, Izz, Ixy, Iyz, Izx]
  double com_margin = 0.0;
  bool stands = false;
  long long self_intersecting_pairs = 0;  // the input's own (geometry/mesh_defects.h)
  bool self_intersections_truncated = false;
};

// One round of the contoured cavity (cavity/contour_cavity.h) and its verification.
struct ContourRound {
  Vector10d delta_in_frame = Vector10d::Zero();  // contour minus offset model, inner integrals
  double void_volume_offset = 0.0, void_volume_contour = 0.0;
  Eigen::Vector3i grid = Eigen::Vector3i::Zero();  // nodes along x, y, z
  double spacing = 0.0;
  long long contoured_cells = 0, distance_nodes = 0;
  int shells = 0, shells_filled = 0;
  double filled_volume = 0.0;
  int vertices_moved_for_wall = 0;
  long long vertices = 0, faces = 0;
  bool goal_met = false;
  std::optional<bool> valid;        // absent when a correction follows (validity not measured)
};

enum class WrittenCavity { offset, contour, quadric };
const char* to_string(WrittenCavity written);

// The contour's own figures of a round (grid, cells, shells, faces) and the goal met; `valid` only
// when validity was measured. The caller sets Δ and the void volumes.
ContourRound contour_round(const ContourCavity& contoured, const Verification& verification, bool validity_measured);

// The offset model corrected for its folds before the first contour (cavity/fold_integrals.h).
struct FoldCorrection {
  double void_volume = 0.0;          // the folds' void volume, input units (the contour holds that much more)
  double wall_cut_volume = 0.0;      // the wall's cut, input units (<= 0: void the contour leaves solid)
  double predicted_violation = 0.0;  // the largest margin row with both, normalised frame (> 0: missed)
};

// Which cavity was written and why: the offset surface's own verification, then the contour rounds,
// then, where the offset model fell short of a goal some void reaches, the quadric void's rounds.
// Objectives are the goal's (shape/goal.h, normalised frame) on the solid as written.
struct CavitySummary {
  CavityMode mode = CavityMode::automatic;
  bool offset_goal_met = false;
  std::optional<bool> offset_valid;  // absent when only the goal was checked (the quadric void decided first)
  std::vector<std::string> offset_failures;
  std::optional<FoldCorrection> fold_correction;    // present when the model was corrected for folds first
  std::optional<std::vector<ContourRound>> rounds;  // present when a contour was attempted
  std::optional<std::vector<ContourRound>> quadric_rounds;  // present when the quadric void was attempted
  std::optional<double> offset_objective, quadric_objective;  // of each void that verified
  WrittenCavity written = WrittenCavity::offset;
  std::string choice;               // why this cavity was written (empty: the only one tried)
  bool contoured() const { return written != WrittenCavity::offset; }
};

// How close the written void comes to the best any void reaches (cavity/reachability.h): the
// fraction of the possible lowering of the centre of mass achieved (stand, stand-filled,
// roly-poly; heights over the ground) or of the best depth under the centre of buoyancy (float).
struct Optimality {
  double fraction = 0.0;
  double before = 0.0, written = 0.0, best = 0.0;  // input units: cz over the ground, or depth
};

// The openings cut through the written cavity (drain holes, the channel of --fix with a contoured
// cavity): what was cut and the figures the verification read on the cut solid.
struct OpeningsSummary {
  std::vector<CutOpening> openings;
  int cavity_shells = 0;
  std::optional<double> spill_height;  // the channel's lowest exit: the liquid's level
  double void_volume = 0.0;            // cavity and openings, input units
  std::optional<double> liquid_volume; // stand-filled with a channel
  bool closed = false;
  long long new_pairs = 0;
  int chips_dropped = 0;               // loose pieces of material the cuts made, dropped
  int rounds = 0;                      // cuts made (a correction between two)
  std::string message;                 // why the openings failed, if they did
};

// Seconds per stage: not reproducible, so kept apart from the rest. contour and correct are
// present when a contour was attempted.
struct StageTimings {
  double frame = 0.0, skeleton = 0.0, basis = 0.0, solve = 0.0, verify = 0.0;
  std::optional<double> contour, correct, reach, quadric, openings;
  std::optional<double> coarse;  // the coarse copy (above 60,000 vertices), alongside the reachability
  double total = 0.0;
};

struct OptimizeResult {
  OptimizeStatus status = OptimizeStatus::bad_input;
  std::string message;          // one line: why it failed (empty when verified)
  Mesh inner, outer, printable, skeleton;  // input units
  // What the report states (set unless status is bad_input):
  GoalSetup goal;
  FrameSummary frame;
  FieldSummary field;
  BasisSummary basis;
  SolverSummary solver;
  InputSummary before;
  CavitySummary cavity;
  Verification after;           // of the written solid
  std::optional<Optimality> optimality;  // when a void reaches the goal and the written one meets it
  StageTimings timings;
  std::vector<std::string> warnings;
  // Whether any void reaches the goal (optimize/reachability_stage.h); absent when it was not
  // asked (bad input).
  std::optional<ReachabilitySummary> reachability;
  std::optional<OpeningsSummary> openings;  // when drain holes or a channel were cut
};

OptimizeResult optimize_offsets(const Mesh& input, const OptimizeOptions& options,
                                const std::function<void(const std::string&)>& progress = {});

}  // namespace offsetopt
