// Stage "reachability" of the pipeline (docs/design.md "Reachability: what any void can do"): before
// the offset solve, can any void reach the goal as posed (cavity/reachability.h)? When no void can
// (decided, with a certificate), the run stops at once with exit 3 and says by how much, and which
// remedies the same programme finds to reach it: --outer (with its band), other faces down
// (--pose stable, --up), the smallest flat base (--flatten H). When it can, the
// run goes on and the report still carries the answer.
//
// "Reachable" is read on the mid cells (CarvableCells::mid: the contour's void, which reaches the
// wall exactly, at the cell scale), so lowest_cz estimates the best void at the requested wall;
// "unreachable" only with a certificate checked on the outer cells.
//
// Input units throughout: best margins are the distance inside the support polygon (stand,
// stand-filled), below the sphere centre (roly-poly) or below the centre of buoyancy (float),
// positive when met; none for spin and volume. lowest_cz is over the ground plane.
#pragma once
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "cavity/reachability.h"
#include "geometry/bvh.h"
#include "mesh/mesh.h"
#include "shape/goal.h"

namespace offsetopt {

struct ReachabilityRemedy {
  std::string option;                // "--outer"
  bool reachable = false;            // the programme reaches the goal with it (mid cells; --outer, --flatten: inner ones too)
  bool decided = false;              // reachable, or proved out of reach by a checked certificate
  // Not reachable, but the mid cells reach it (a void whose cells' centres keep the wall, half a
  // cell past it at most); the inner cells do not: named as undecided (--outer, --flatten H).
  bool mid_cells_reach = false;
  std::optional<double> best_margin;
};

struct ReachabilitySummary {
  bool reachable = false, decided = false;
  // What decided it: "programme" (a void of mid cells reaches the goal), "certificate" (a checked
  // certificate proves no void does), "written solid" (the programme could not tell, or found less,
  // and the run's verified solid meets the goal: optimize sets this after the verification), or
  // empty (undecided).
  std::string evidence;
  // The claim "reachable" was read again on the inner cells (confirm_reachable): it stands only
  // where they reach the goal too.
  bool inner_reading = false;
  std::optional<double> best_margin, best_margin_upper;
  std::string binding;
  std::optional<double> lowest_cz;
  bool certificate = false;          // a certificate was checked (it proves when decided and unreachable)
  Eigen::Vector3d certificate_origin = Eigen::Vector3d::Zero();
  Vector10d quadric = Vector10d::Zero();  // q(p) = Σ quadric_k m_k(p − origin); void = {q < 0}
  double carvable_volume = 0.0;
  // The cells' spacing the answer was read on, input units: the contour's, or half of it when the
  // contour's could not decide (docs/reachability.md "Finer cells").
  double cell_spacing = 0.0;
  int lps = 0;
  long long lp_iterations = 0;
  std::vector<ReachabilityRemedy> remedies;
  std::string shortfall;             // when decided unreachable: by how much, in the goal's terms, input units
  std::string refusal;               // when refused before the solve: the one-line reason, remedies and all
  std::string remedy_list;           // the remedies that reach the goal ("--outer, --up +y"), or empty
  std::string undecided_remedies;    // those only the mid cells reach (mid_cells_reach: "--outer"), or empty
  std::string no_remedy_hint = "re-pose the model or thicken it";  // what to do when no remedy tried reaches it
  // Not reported: the programme itself (cells, occupancy, the optimum's quadric) and how it was
  // set, for the quadric void (optimize/quadric_void.h); null when it could not be set up.
  std::shared_ptr<const Reachability> programme;
  ReachabilityOptions options;
};

struct ReachabilityStageInput {
  const Mesh* input = nullptr;       // as posed
  GoalSpec goal;                     // input units (OptimizeOptions' goal as make_frame sets it)
  double ground_z = 0.0;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // the ground contact centroid on the ground
  double wall = 0.0, outer_max = 0.0, ground_tol = 0.0;
  bool outer = false;
  double cavity_cells_per_wall = 1.5, cavity_margin_cells = 0.0;
  int threads = 2;
  double flatten = 0.0;              // the --flatten height the input was already cut at (0: none)
  const TriangleBvh* input_bvh = nullptr;  // the input's tree when built already (else built here)
  // How the file's mesh was turned into `input` (the CLI's pose options): the --up axis, and
  // whether --pose stable was given. A pose remedy names what to type for the file, so with --up
  // +x an "--up +y" remedy is the file's +y up, not the turned mesh's.
  std::string up = "+z";
  bool posed_stable = false;
  std::optional<ReachabilityOptions::Line> volume_start;  // ReachabilityOptions::volume_start
  // ReachabilityOptions::share_levels: where whole generous cells decide nothing, their shell is
  // counted in part before cells half as large are tried (0: whole cells, then finer ones).
  int share_levels = ReachabilityOptions::defaults().share_levels;
  // ReachabilityOptions::bound_undecided: the generous reading to its optimum (for a refusal's
  // bracket), not only until it clears the user's margin.
  bool bound_undecided = false;
};

ReachabilitySummary reachability_stage(const ReachabilityStageInput& in);

// For a run that missed a goal the mid reading calls reachable (its cells reach half a cell past
// the wall, so near the limit it is an estimate): whether a void the tool can write reaches it,
// read on the inner cells (every corner passes the contour's node test), on the contour's cells
// and, where they cannot tell, on cells half as large. Where neither shows one, the summary is
// made undecided, with the inner reading's best margin and the generous reading's bound (or
// proved out of reach where its certificate proves it). The remedies are not added here.
void confirm_reachable(const ReachabilityStageInput& in, ReachabilitySummary& summary);

// For a run that missed a goal the programme left undecided: the generous reading read to its
// optimum (the stage stops it once it clears the user's margin, where it can no longer prove the
// goal out of reach), so that the refusal prints the bracket, best_margin_upper. `in` as the stage
// had it (the programme is read again with bound_undecided set).
void bound_undecided(const ReachabilityStageInput& in, ReachabilitySummary& summary);

// The remedies, each checked by the same programme, into `summary` (remedies, remedy_list): the
// stage adds them itself to a proved refusal; for an undecided goal the pipeline asks only once
// the run has missed it (six pose programmes and the --outer band cost more than many solves that
// then meet the goal). Does nothing for a reachable goal or when they are already there.
void add_remedies(const ReachabilityStageInput& in, ReachabilitySummary& summary);

// For a run that missed the goal: what the programme found, in one clause. Proved out of reach
// (confirm_reachable's certificate): "no void can reach this: ...; try ...". Undecided: "undecided
// whether any void reaches it (best margin -0.0087 to -0.0013); try --pose stable; undecided with --outer";
// reachable: "a void the tool can write reaches it (best margin 0.4), so this is the tool's
// shortfall, not the model's".
std::string reachability_note(const ReachabilitySummary& summary);

}  // namespace offsetopt
