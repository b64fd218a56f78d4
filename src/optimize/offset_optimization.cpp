#include "optimize/offset_optimization.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <future>
#include <limits>
#include <memory>
#include <optional>

#include <Eigen/Cholesky>

#include "geometry/bvh.h"
#include "geometry/intersecting_faces.h"
#include "geometry/mesh_defects.h"
#include "geometry/pose.h"
#include "mass/mass_properties.h"
#include "mass/stability.h"
#include "mass/volume_integrals.h"
#include "cavity/contour_cavity.h"
#include "cavity/fold_integrals.h"
#include "shape/lipschitz_envelope.h"
#include "shape/offset_field.h"
#include "shape/outer_offset_limit.h"
#include "shape/shrink_outer_limit.h"
#include "cavity/new_self_intersections.h"
#include "cavity/open_cavity.h"
#include "cavity/printable_solid.h"
#include "cavity/verify_opened_cavity.h"
#include "cavity/round_for_output.h"
#include "cavity/verify_offsets.h"
#include "optimize/quadric_void.h"
#include "skeleton/laplacian_contraction.h"
#include "util/format_double.h"
#include "util/parallel.h"
#include "util/seconds_since.h"

namespace offsetopt {

namespace {

using Clock = std::chrono::steady_clock;

// Algebraic least-squares sphere |x|² = 2 c·x + d through the vertices of the bottom part.
bool fit_bottom_sphere(const Mesh& mesh, double zmin, double height, Eigen::Vector3d& center, double& radius) {
  for (double fraction : {0.25, 0.4, 0.6}) {
    Eigen::Matrix4d normal = Eigen::Matrix4d::Zero();
    Eigen::Vector4d rhs = Eigen::Vector4d::Zero();
    int used = 0;
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
      const Eigen::Vector3d p = mesh.V.row(i).transpose();
      if (p.z() > zmin + fraction * height) continue;
      const Eigen::Vector4d row(2 * p.x(), 2 * p.y(), 2 * p.z(), 1.0);
      normal += row * row.transpose();
      rhs += row * p.squaredNorm();
      ++used;
    }
    if (used < 10) continue;
    const Eigen::Vector4d s = normal.ldlt().solve(rhs);
    center = s.head<3>();
    const double r2 = s(3) + center.squaredNorm();
    if (!(r2 > 0.0) || !s.allFinite()) continue;
    radius = std::sqrt(r2);
    return true;
  }
  return false;
}

OptimizeResult failure(OptimizeStatus status, const std::string& message) {
  OptimizeResult r;
  r.status = status;
  r.message = message;
  return r;
}

}  // namespace

const char* to_string(CavityMode mode) {
  switch (mode) {
    case CavityMode::automatic: return "auto";
    case CavityMode::offset: return "offset";
    case CavityMode::contour: return "contour";
    case CavityMode::quadric: return "quadric";
  }
  return "auto";
}

ContourRound contour_round(const ContourCavity& contoured, const Verification& verification, bool validity_measured) {
  ContourRound entry;
  entry.grid = Eigen::Vector3i(static_cast<int>(contoured.grid.nx), static_cast<int>(contoured.grid.ny),
                               static_cast<int>(contoured.grid.nz));
  entry.spacing = contoured.grid.spacing;
  entry.contoured_cells = contoured.active_cells;
  entry.distance_nodes = contoured.distance_nodes;
  entry.shells = contoured.shells;
  entry.shells_filled = contoured.shells_dropped;
  entry.filled_volume = contoured.dropped_volume;
  entry.vertices_moved_for_wall = contoured.vertices_moved_for_wall;
  entry.vertices = static_cast<long long>(contoured.cavity.V.rows());
  entry.faces = static_cast<long long>(contoured.cavity.F.rows());
  entry.goal_met = verification.goal_met;
  if (validity_measured) entry.valid = verification.valid;
  return entry;
}

const char* to_string(WrittenCavity written) {
  switch (written) {
    case WrittenCavity::offset: return "offset";
    case WrittenCavity::contour: return "contour";
    case WrittenCavity::quadric: return "quadric";
  }
  return "offset";
}

bool parse_cavity_mode(const std::string& text, CavityMode& mode) {
  for (CavityMode m : {CavityMode::automatic, CavityMode::offset, CavityMode::contour, CavityMode::quadric})
    if (text == to_string(m)) {
      mode = m;
      return true;
    }
  return false;
}

std::string OptimizeOptions::check() const {
  const OptimizeOptions& s = *this;
  if (s.k < 0) return "--k must be >= 1 or 'all'";
  auto finite_or_default = [](double v) { return std::isfinite(v); };
  for (double v : {s.wall, s.outer_max, s.margin, s.ground_tol, s.radius, s.penalty, s.fill_density, s.fluid_density,
                   s.target_volume, s.gap, s.ramp})
    if (!finite_or_default(v)) return "every numeric option must be finite";
  if (s.penalty < 0.0) return "--penalty must be >= 0";
  if (s.goal == GoalKind::stand_filled && !(s.fill_density > 0.0)) return "--fill-density must be > 0";
  if (s.goal == GoalKind::floating && !(s.fluid_density > 0.0 && s.fluid_density < 1.0))
    return "--goal float needs --fluid-density in (0, 1) (relative to the material)";
  if (s.goal == GoalKind::volume && !(s.target_volume > 0.0)) return "--goal volume needs --target-volume > 0";
  if (!(s.gap >= 0.0 && s.gap < 1.0)) return "gap must be in [0, 1)";
  if (!(s.ramp > 0.0)) return "ramp must be > 0";
  if (s.outer && s.bounds == BoundsMode::hard && s.k == 0) return "--k all with --bounds hard and --outer is not supported";
  if (s.threads < 1 || s.threads > 64) return "--threads must be in [1, 64]";
  if (AxisPermutation axis; !up_axis_permutation(s.up, axis)) return "--up must be +x, -x, +y, -y, +z or -z, got '" + s.up + "'";
  if (s.max_correction_rounds < 0 || s.max_correction_rounds > 20) return "correction rounds must be in [0, 20]";
  if (s.wants_drain_holes() && s.cavity == CavityMode::offset)
    return "drain holes are cut through a contoured cavity: use --cavity auto, contour or quadric, not offset";
  if (!(s.drain_hole_radius < 0.0 || (std::isfinite(s.drain_hole_radius) && s.drain_hole_radius > 0.0)))
    return "--drain-hole-radius must be > 0";
  for (const DrainHoleRequest& h : s.drain_holes)
    if (!h.point.allFinite() || !(h.radius < 0.0 || h.radius > 0.0)) return "--drain-hole needs a finite point and a radius > 0";
  ContourCavityOptions contour;
  contour.wall = 1.0;
  contour.cells_per_wall = s.cavity_cells_per_wall;
  contour.margin_cells = s.cavity_margin_cells;
  if (const std::string problem = contour.check(); !problem.empty()) return "cavity: " + problem;
  return s.solver.check();
}

namespace {

using Progress = std::function<void(const std::string&)>;

constexpr double kCorrectionHeadroom = 0.01;  // see OffsetSolve::correct
// The first penalty of the correction made for folds before the first contour, at most (a later
// round's is at most OptimizeOptions::warm_penalty_cap). That shift is a prediction of a few 1e-4
// of the frame and the solve it corrects has just converged: the demo bottle standing filled with
// --outer corrects in 132 evaluations from 1e3, 93 from 1e4. Not for every round: 1e4 as
// warm_penalty_cap cost the census's roly-poly 16%, whose corrections follow a contour; the
// census (standing, filled with --outer, roly-poly) makes no fold correction.
constexpr double kFoldCorrectionPenaltyCap = 1e4;
// The first solve's iterate within this violation (normalised frame; the solver's tolerance is
// 1e-8) is asked whether its folds already call for that correction: when they do, the solve ends
// there and the correction goes on from it, since the corrected solve would undo the last digits
// anyway. The demo bottle standing filled with --outer: 306 + 93 evaluations before, 247 + 100.
constexpr double kFoldHandOffViolation = 1e-7;
// A sphere fitted to the bottom this many diagonals wide: the bottom is flat (cgal-data_pinion:
// radius 1228, 527 diagonals; every other roly-poly of the census is under one diagonal).
constexpr double kFlatBottomDiagonals = 10.0;
constexpr double kFinestQuadricCellsPerWall = 3.0;  // one refinement of the default 1.5
// How far below its model's objective a contour's may fall, relative: on the census (56 contours
// that verified) at most 1.4e-4 (a sphere), every other one above it.
constexpr double kContourBelowModel = 1e-3;
// See OffsetSolve::solve: the first kOuterFoldHalvings repairs halve the folding faces' limits,
// the rest set them to 0, and each repair is searched again, up to kOuterFoldRepairs. Four with
// the last at 0 and no search after it left cgal-data_man standing filled with --outer with 2
// new crossing pairs (exit 3 on a goal a void reaches): a fold moves next door when its own
// vertices stop.
constexpr int kOuterFoldHalvings = 3;
constexpr int kOuterFoldRepairs = 8;

// The solve met the goal's constraints: neither infeasible nor stopped, and violated by at most
// 100 times the solver's feasibility tolerance (normalised frame); a NaN violation is not met.
bool constraints_met(const AlResult& solved, const OptimizeOptions& options) {
  return solved.status != AlStatus::infeasible && solved.status != AlStatus::stopped &&
         solved.max_violation <= 100.0 * options.solver.feasibility_tolerance;
}

// A solid that meets the goal and is valid, as verified.
bool verified(const Verification& v) { return v.goal_met && v.valid; }

// Stage "frame": ground, support polygon, scale, and the goal in input units (for verification)
// and in the normalised frame (for the solver).
struct Frame {
  double diag = 1.0, scale = 1.0;
  double wall = 0.0, outer_max = 0.0, margin = 0.0, ground_tol = 0.0;  // input units
  Eigen::Vector3d lo, hi, origin;
  Eigen::Vector2d contact_centroid = Eigen::Vector2d::Zero();
  double zmin = 0.0;
  Vector10d before;
  Stability stability_before;
  Mesh normalized;
  GoalSpec goal_input, goal;
  // The void's volume within this fraction of the target: the verification's, but tighter for a
  // void aimed below the target that openings fill up (quadric_void_aimed_at).
  double volume_tolerance = 1e-4;
  GoalSetup setup;
  Eigen::Vector3d to_frame(const Eigen::Vector3d& p) const { return (p - origin) * scale; }
};

// The ten volume integrals of a surface in the normalised frame (origin, 1 / diagonal).
Vector10d integrals_in_frame(const Frame& f, const Mesh& mesh) {
  Mesh framed = mesh;
  for (Eigen::Index i = 0; i < framed.V.rows(); ++i) framed.V.row(i) = f.to_frame(framed.V.row(i).transpose()).transpose();
  return volume_integrals(framed, Eigen::Vector3d::Zero()).values;
}

// What every verification of a written solid takes from the frame and the options: the goal,
// its tolerances, the wall and the output's precision (the surfaces are set per use).
VerifyInput verify_input_for(const OptimizeOptions& options, const Frame& f) {
  VerifyInput v;
  v.goal = f.goal_input;
  v.diagonal = f.diag;
  v.ground_tol = f.ground_tol;
  v.wall = f.wall;
  v.volume_tolerance = f.volume_tolerance;
  v.threads = options.threads;
  v.precision = options.output_precision;
  return v;
}

// Empty when the frame and goal are set, else why the input does not allow the goal.
std::string make_frame(const Mesh& input, const OptimizeOptions& options, Frame& f) {
  const Eigen::Index n = input.V.rows();
  f.lo = input.V.colwise().minCoeff().transpose();
  f.hi = input.V.colwise().maxCoeff().transpose();
  f.diag = (f.hi - f.lo).norm();
  f.scale = 1.0 / f.diag;
  auto length = [&](double value, double fraction) { return value >= 0.0 ? value : fraction * f.diag; };
  f.wall = length(options.wall, 0.01);
  f.outer_max = length(options.outer_max, 0.02);
  f.margin = length(options.margin, 0.002);
  f.ground_tol = length(options.ground_tol, 0.001);
  f.before = mass_properties(input);
  StabilityOptions stability_options;
  stability_options.ground_tol = f.ground_tol;
  f.stability_before =
      compute_stability(input, Eigen::Vector3d(f.before(kCx), f.before(kCy), f.before(kCz)), stability_options);
  f.zmin = f.stability_before.ground_z;
  int contacts = 0;
  for (Eigen::Index i = 0; i < n; ++i)
    if (input.V(i, 2) <= f.zmin + f.ground_tol) {
      f.contact_centroid += input.V.row(i).head<2>().transpose();
      ++contacts;
    }
  f.contact_centroid /= contacts;
  f.origin = Eigen::Vector3d(f.contact_centroid.x(), f.contact_centroid.y(), f.zmin);
  f.normalized = input;
  for (Eigen::Index i = 0; i < n; ++i) f.normalized.V.row(i) = f.to_frame(input.V.row(i).transpose()).transpose();

  GoalSpec& g = f.goal_input;
  g.kind = options.goal;
  g.margin = f.margin;
  g.epsilon = f.margin;
  g.fill_density = options.fill_density;
  g.fluid_density = options.fluid_density;
  g.target_volume = options.target_volume;
  g.support_polygon = f.stability_before.support_polygon;
  f.setup.kind = options.goal;
  if (options.goal == GoalKind::roly_poly) {
    Eigen::Vector3d center;
    double radius = options.radius;
    if (radius > 0.0) {
      Eigen::Index lowest = 0;
      input.V.col(2).minCoeff(&lowest);
      center = Eigen::Vector3d(input.V(lowest, 0), input.V(lowest, 1), f.zmin + radius);
    } else if (!fit_bottom_sphere(input, f.zmin, f.hi.z() - f.lo.z(), center, radius)) {
      return "no sphere could be fitted to the bottom; give --radius";
    }
    g.axis_point = center;
    f.setup.sphere_center = center;
    f.setup.sphere_radius = radius;
  } else if (options.goal == GoalKind::spin) {
    Eigen::Index lowest = 0;
    input.V.col(2).minCoeff(&lowest);
    g.axis_point = input.V.row(lowest).transpose();
    f.setup.tip = g.axis_point;
  } else if (options.goal == GoalKind::volume && options.target_volume >= f.before(kMass)) {
    return "--target-volume " + format_double(options.target_volume) + " is not below the object's volume " +
           format_double(f.before(kMass));
  }
  if (const std::string problem = check_goal_spec(g); !problem.empty()) return problem;
  f.goal = g;
  for (auto& p : f.goal.support_polygon) p = (p - f.contact_centroid) * f.scale;
  // A hair of extra margin so the constraint met to the solver's tolerance is met exactly.
  f.goal.margin = f.margin * f.scale + 1e-7;
  f.goal.epsilon = f.margin * f.scale + 1e-7;
  f.goal.axis_point = f.to_frame(g.axis_point);
  f.goal.target_volume = options.target_volume * f.scale * f.scale * f.scale;
  return "";
}

// Stage "band": the meso-skeleton, the offset field and the per-vertex band the offsets move in.
struct Band {
  ContractionResult contraction;
  std::shared_ptr<const TriangleBvh> bvh;  // of the input, shared with the reachability and the quadric void
  SelfIntersectionReport input_self;  // the input's own self-intersections (as `check` counts them)
  std::vector<std::pair<int, int>> input_pairs;  // with --outer: the pairs the outer surface may keep
  OuterOffsetLimit outer;          // with --outer: how far each vertex may thicken, input units
  OuterLimitSummary outer_summary;
  OffsetField field;
  OffsetBand band;
  int fixed_count = 0;
  std::vector<char> left_solid;    // per vertex: in a part left solid (an empty band, lower >= upper)
  int left_solid_count = 0, left_solid_count_initial = 0;

  void mark_left_solid() {
    left_solid_count = 0;
    left_solid.assign(band.fixed.size(), 0);
    for (std::size_t i = 0; i < left_solid.size(); ++i) {
      const Eigen::Index v = static_cast<Eigen::Index>(i);
      left_solid[i] = !band.fixed[i] && band.lower(v) >= band.upper(v);
      left_solid_count += left_solid[i];
    }
  }
};

// The input's own crossings as a search capped at 10^5 pairs counts them (pairs, truncated): from
// the input boundary's search when given (its larger cap finds the same pairs below this one),
// else searched.
SelfIntersectionReport input_self_intersections(const Mesh& input, const OptimizeOptions& options) {
  const long long cap = 100000;
  if (!options.input_self_intersections) return find_self_intersections(input, cap);
  SelfIntersectionReport known = *options.input_self_intersections;
  if (known.pairs >= cap) {
    known.pairs = cap;
    known.truncated = true;
  }
  return known;
}

std::string make_band(const Mesh& input, const std::shared_ptr<const TriangleBvh>& input_bvh, const OptimizeOptions& options,
                      const Frame& f, const CoarseCopy* coarse, Band& b) {
  const Eigen::Index n = input.V.rows();
  const auto& tick = options.on_stage_progress;
  ContractionOptions contraction_options;
  contraction_options.threads = options.threads;
  if (tick) contraction_options.on_progress = [&tick](double fraction) { tick("skeleton", 0.7 * fraction); };
  b.contraction = coarse ? laplacian_contraction_of_copy(*coarse, contraction_options)
                         : laplacian_contraction(input.V, input.F, contraction_options);
  b.bvh = input_bvh;
  b.input_self = input_self_intersections(input, options);
  OffsetFieldOptions field_options;
  field_options.wall = f.wall;
  field_options.threads = options.threads;
  if (tick) tick("skeleton", 0.75);
  b.field = offset_field(input, b.contraction.V, *b.bvh, field_options);
  OffsetBand& band = b.band;
  band.inner_direction = b.field.inner;
  band.outer_direction = b.field.outer;
  band.lower = b.field.lower * f.scale;
  band.upper = lipschitz_envelope(f.normalized, b.field.upper * ((1.0 - options.gap) * f.scale), options.bound_slope);
  band.fixed = fixed_vertices(input, options.fix);
  for (char fixed : band.fixed) b.fixed_count += fixed ? 1 : 0;
  if (options.fix.kind != FixRegion::Kind::none && b.fixed_count == 0)
    return "--fix " + options.fix.text + " selects no vertex";
  if (options.outer) {
    b.input_pairs = self_intersections(*b.bvh, 100000).pairs;
    // The base stays where it is: no outer offset at or below b = zmin + 2 ground_tol, and above it
    // a vertex may drop (|w_z| times its offset, either sign) at most 0.9 of its height above b, so
    // it stays above b: the contact set and the pose are kept (half its height cost the horse's
    // stand margin: 0.92 of the request).
    Eigen::VectorXd requested(n);
    const double base = f.zmin + 2.0 * f.ground_tol;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double height = input.V(i, 2) - base;
      const double drop_per_offset = std::fabs(b.field.outer(i, 2));
      double wanted = f.outer_max;
      if (drop_per_offset * wanted > 0.9 * height) wanted = 0.9 * height / drop_per_offset;
      requested(i) = height <= 0.0 || band.fixed[static_cast<std::size_t>(i)] ? 0.0 : wanted;
    }
    // Each vertex thickens at most as far as the surface cannot fold there (shape/outer_offset_limit.h).
    OuterOffsetLimitOptions limit_options;
    limit_options.threads = options.threads;
    b.outer = outer_offset_limit(input, *b.bvh, b.field.outer, b.field.normals, requested, limit_options);
    band.outer_limit = b.outer.limit * f.scale;
    b.outer_summary = {b.outer.free_limited, b.outer.focal_limited, b.outer.nearest_limited, 0.0, 0};
    int away = 0;
    for (Eigen::Index i = 0; i < n; ++i)
      if (requested(i) > 0.0) {
        b.outer_summary.mean_fraction += b.outer.limit(i) / f.outer_max;
        ++away;
      }
    if (away > 0) b.outer_summary.mean_fraction /= away;
  }
  b.mark_left_solid();
  b.left_solid_count_initial = b.left_solid_count;
  return "";
}

// The largest of the goal's inequality rows (normalised frame, > 0 where missed) on the integrals
// given: the margins the goal asks for (inside the support polygon, below a centre).
double largest_inequality(const GoalSpec& goal, const Vector10d& outer, const Vector10d& inner) {
  const GoalValues values = evaluate_goal(goal, outer, inner);
  double largest = -std::numeric_limits<double>::infinity();
  for (Eigen::Index r = 0; r < values.inequality.size(); ++r) largest = std::max(largest, values.inequality(r));
  return largest;
}

// What the folds of one solution's offset surfaces predict for its first contour (see
// correct_for_folds): the folds' integrals, and where they alone miss a margin row, the wall's cut
// too; `miss` when both together miss it, which calls for a correction by `shift`.
struct FoldPrediction {
  FoldIntegrals folds;
  std::optional<WallCutIntegrals> cut;
  Vector10d shift = Vector10d::Zero();  // folds, cut and the openings' void (frame)
  double predicted = 0.0;               // the largest inequality row with the shift
  bool miss = false;
};

FoldPrediction predict_folds(const OptimizeOptions& options, const Frame& f, const Band& b, const Mesh& outer, const Mesh& inner,
                             const ReducedProblem::Evaluation& eval, const ContourCavityOptions& cavity_options,
                             const Vector10d& opening_void) {
  FoldPrediction p;
  p.folds = fold_integrals(outer, inner, cavity_options, f.origin, f.scale);
  if (!p.folds.ok || p.folds.folded_nodes == 0) return p;
  const double tolerance = options.solver.feasibility_tolerance;
  auto worst_row = [&](const Vector10d& shift) { return largest_inequality(f.goal, eval.outer_integrals, eval.inner_integrals + shift); };
  if (!(worst_row(p.folds.integrals + opening_void) > tolerance)) return p;
  std::optional<TriangleBvh> offset_bvh;
  const TriangleBvh& outer_bvh = options.outer ? offset_bvh.emplace(outer.V, outer.F) : *b.bvh;
  p.cut = wall_cut_integrals(outer, outer_bvh, p.folds, cavity_options, f.origin, f.scale);
  p.shift = p.folds.integrals + p.cut->integrals + opening_void;
  p.predicted = worst_row(p.shift);
  p.miss = p.predicted > tolerance;
  return p;
}

// The contour's options for the offset void of `outer`: the wall survives the rounding of both
// surfaces to the output's precision.
ContourCavityOptions offset_contour_options(const OptimizeOptions& options, const Frame& f, const Mesh& outer) {
  ContourCavityOptions o;
  o.wall = f.wall + rounding_wall_margin(outer.V.size() ? outer.V.cwiseAbs().maxCoeff() : 0.0, options.output_precision);
  o.cells_per_wall = options.cavity_cells_per_wall;
  o.margin_cells = options.cavity_margin_cells;
  o.threads = options.threads;
  return o;
}

// Stage "solve": the reduced problem, solved from x, again after each repair (`--cavity offset`)
// or correction (the contoured cavity's moments) from where the last solve ended.
class OffsetSolve {
 public:
  OffsetSolve(const Mesh& input, const OptimizeOptions& options, const Frame& f, Band& b,
              const Eigen::MatrixXd& basis, const ReducedOptions& reduced_options, const Progress& say)
      : input_(input), options_(options), f_(f), b_(b), basis_(basis), reduced_options_(reduced_options), say_(say) {}

  // The first solve and, with `--cavity offset`, the repair rounds.
  void run() {
    const int max_repair_rounds = options_.cavity == CavityMode::offset ? options_.max_repair_rounds : 0;
    const Eigen::Index n = input_.V.rows();
    for (int round = 0;; ++round) {
      problem_ = std::make_unique<ReducedProblem>(f_.normalized, b_.band, basis_, options_.k == 0, f_.goal, reduced_options_);
      variables = problem_->num_variables();
      if (round == 0) {
        x_ = warm_ && warm_->x.size() == variables ? warm_->x : problem_->start_point();
        say_("solve: " + std::to_string(variables) + " variables, goal " + to_string(options_.goal));
      }
      // Tightened bounds only shrink the feasible set: when the goal's constraints are not met,
      // repairs cannot help, and the report says why.
      if (solve(round)) last_round_met = round;
      if (round == max_repair_rounds || !constraints_met || stopped()) break;
      const SurfaceDefects defects =
          find_surface_defects(outer, inner, b_.band.fixed, b_.left_solid, 0.5 * f_.wall, options_.threads);
      if (defects.empty()) break;
      ++repair_rounds;
      repairs.push_back({static_cast<long long>(defects.intersecting_vertices.size()),
                         static_cast<long long>(defects.thin_wall_vertices.size())});
      say_("repair " + std::to_string(repair_rounds) + ": " + std::to_string(defects.intersecting_vertices.size()) +
           " vertices on folds, " + std::to_string(defects.thin_wall_vertices.size()) + " on thin walls");
      // A fold spans the faces around its vertices: their one-ring neighbours are tightened too,
      // or the fold moves next door and needs another round.
      std::vector<char> tighten(static_cast<std::size_t>(n), 0);
      for (int v : defects.intersecting_vertices) tighten[static_cast<std::size_t>(v)] = 1;
      if (options_.repair_ring)
        for (Eigen::Index face = 0; face < input_.F.rows(); ++face) {
          bool touched = false;
          for (int c = 0; c < 3; ++c) touched = touched || tighten[static_cast<std::size_t>(input_.F(face, c))] == 1;
          if (touched)
            for (int c = 0; c < 3; ++c) {
              char& mark = tighten[static_cast<std::size_t>(input_.F(face, c))];
              if (mark == 0) mark = 2;
            }
        }
      OffsetBand& band = b_.band;
      for (Eigen::Index v = 0; v < n; ++v)
        if (tighten[static_cast<std::size_t>(v)]) band.upper(v) *= options_.repair_shrink;
      band.upper = lipschitz_envelope(f_.normalized, band.upper, options_.bound_slope);
      for (int v : defects.thin_wall_vertices) band.lower(v) += 0.5 * f_.wall * f_.scale;
      b_.mark_left_solid();
    }
  }

  // Solves again with the goal read on the inner integrals plus `shift`, warm-started, aiming
  // kCorrectionHeadroom of the user's margins inside them: the solver stops on the boundary of an
  // inequality, and the next contour's moments differ from this one's by a little noise (on
  // rocker_arm.off --flatten 0.0436 the margin was missed by 5e-4 of itself after 6 rounds).
  // `penalty_cap`: the first penalty at most (0: OptimizeOptions::warm_penalty_cap).
  bool correct(const Vector10d& shift, int round, double penalty_cap = 0.0) {
    round_cap_ = penalty_cap;
    problem_->set_inner_integral_shift(shift);
    corrected_ = true;
    const double grow = 1.0 + kCorrectionHeadroom;
    problem_->set_goal_margins(f_.margin * f_.scale * grow + 1e-7, f_.margin * f_.scale * grow + 1e-7);
    if (solve(round)) last_round_met = round;
    round_cap_ = 0.0;
    return constraints_met;
  }

  // The largest violation of the enforced band, input units.
  double bound_violation() const {
    double worst = 0.0;
    for (Eigen::Index i = 0; i < input_.V.rows(); ++i) {
      if (b_.band.fixed[static_cast<std::size_t>(i)]) continue;
      const double upper = b_.band.upper(i) / f_.scale;
      const double lower = std::min(b_.band.lower(i) - eval.outer_offset(i), b_.band.upper(i)) / f_.scale;
      const double offset = eval.inner_offset(i) / f_.scale;
      worst = std::max({worst, offset - upper, lower - offset});
    }
    return worst;
  }

  // Start the first solve from another solve's end (the coarse copy's, coarse_solve).
  void warm_start(AlResult from) { warm_ = std::move(from); }

  // The first solve may end at its first iterate within kFoldHandOffViolation where `predict`,
  // given the offset surfaces and the evaluation there, finds that the folds call for a
  // correction (correct_for_folds then makes it from there, with that prediction).
  using FoldPredictor = std::function<FoldPrediction(const Mesh& outer, const Mesh& inner, const ReducedProblem::Evaluation&)>;
  void hand_off_for_folds(FoldPredictor predict) { predict_folds_ = std::move(predict); }
  // The grid nodes where the inner surface winds neither 0 nor 1 times, as the first solve was
  // handed off on them (0 when it was not); a closed surface clear of itself has none.
  std::int64_t handed_off_folded_nodes() const { return fold_prediction_ ? fold_prediction_->folds.folded_nodes : 0; }
  // The prediction the first solve was handed off on, once (empty when it was not).
  std::optional<FoldPrediction> take_fold_prediction() {
    std::optional<FoldPrediction> p = std::move(fold_prediction_);
    fold_prediction_.reset();
    return p;
  }

  // What the corrections change, kept before a contour that may turn out unwanted
  // (make_offset_cavity) and put back then: the first solve's end, without any correction's shift.
  struct State {
    AlResult solved;
    ReducedProblem::Evaluation eval;
    Mesh inner, outer;
    Eigen::VectorXd x;
    int total_evaluations = 0, last_round_met = -1;
    bool constraints_met = false;
  };
  State state() const { return {solved, eval, inner, outer, x_, total_evaluations, last_round_met, constraints_met}; }
  void restore_uncorrected(State s) {
    solved = std::move(s.solved);
    eval = std::move(s.eval);
    inner = std::move(s.inner);
    outer = std::move(s.outer);
    x_ = std::move(s.x);
    total_evaluations = s.total_evaluations;
    last_round_met = s.last_round_met;
    constraints_met = s.constraints_met;
    problem_->set_inner_integral_shift(Vector10d::Zero());
    problem_->set_goal_margins(f_.goal.margin, f_.goal.epsilon);
    corrected_ = false;
  }

  // Whether the goal reads the inner integrals shifted by a correction (correct) since the first
  // solve or the last restore_uncorrected.
  bool corrected() const { return corrected_; }

  AlResult solved;
  ReducedProblem::Evaluation eval;
  Mesh inner, outer;                // the offset surfaces at the last solve, input units
  int variables = 0, repair_rounds = 0, total_evaluations = 0;
  int last_round_met = -1;          // the last solve that met the goal's constraints
  bool constraints_met = false;
  std::vector<RepairRound> repairs;

  // The solver was stopped from outside (options.solver.stop: the goal was found out of reach).
  bool stopped() const { return solved.status == AlStatus::stopped; }

 private:
  AlOptions params(int round) {
    AlOptions p = options_.solver;
    if (round == 0 && warm_ && warm_->x.size() == variables) {
      // From the coarse copy's solve (coarse_solve): its multipliers and penalty, capped as below.
      p.initial_equality_multipliers = warm_->equality_multipliers;
      p.initial_inequality_multipliers = warm_->inequality_multipliers;
      p.initial_penalty = std::min(warm_->penalty, options_.warm_penalty_cap);
    }
    if (round > 0) {
      // A later round solves a nearby problem: start from the last round's multipliers and
      // penalty (measured on the bottle with --outer: 3605 evaluations without, 1124 with), the
      // penalty capped, because a huge one makes the first subproblem ill-conditioned (roly-poly:
      // 523 evaluations uncapped, 270 capped at 1e3).
      p.initial_equality_multipliers = solved.equality_multipliers;
      p.initial_inequality_multipliers = solved.inequality_multipliers;
      p.initial_penalty = std::min(solved.penalty, round_cap_ > 0.0 ? round_cap_ : options_.warm_penalty_cap);
    }
    if (round == 0 && predict_folds_) {
      p.hand_off_violation = kFoldHandOffViolation;
      p.hand_off = [this](const Eigen::VectorXd& x) {
        // A problem of its own, so that nothing the solve reads is touched.
        ReducedProblem probe(f_.normalized, b_.band, basis_, options_.k == 0, f_.goal, reduced_options_);
        const ReducedProblem::Evaluation& at = probe.evaluate(x);
        Mesh probe_inner, probe_outer;
        surfaces(at, probe_inner, probe_outer);
        FoldPrediction prediction = predict_folds_(probe_outer, probe_inner, at);
        if (!prediction.miss) return false;
        fold_prediction_ = std::move(prediction);
        return true;
      };
    }
    if (options_.on_stage_progress && !options_.trace_solver)
      p.on_outer_iteration = [tick = options_.on_stage_progress, cap = p.max_outer_iterations](const AlIterationInfo& info) {
        tick("solve", std::min(0.99, static_cast<double>(info.outer_iteration) / cap));
      };
    if (options_.trace_solver)
      p.on_outer_iteration = [say = say_, round, tick = options_.on_stage_progress,
                              cap = p.max_outer_iterations](const AlIterationInfo& info) {
        if (tick) tick("solve", std::min(0.99, static_cast<double>(info.outer_iteration) / cap));
        say("  round " + std::to_string(round) + " outer " + std::to_string(info.outer_iteration) + ": f " +
            format_double(info.f) + ", violation " + format_double(info.max_violation) + ", stationarity " +
            format_double(info.stationarity) + ", penalty " + format_double(info.penalty) + ", inner " +
            to_string(info.inner_status) + " after " + std::to_string(info.inner_iterations) + " iterations, " +
            std::to_string(info.evaluations) + " evaluations");
      };
    return p;
  }

  // Solves from x and sets the surfaces; false when the goal's constraints are not met.
  bool solve(int round) {
    minimize(round);
    // The outer limits are local estimates (shape/outer_offset_limit.h): where the thickened
    // surface still folds, its limits there are halved (after kOuterFoldHalvings times, set to 0)
    // and the problem is solved again from where it ended.
    for (int repair = 0; options_.outer && repair < kOuterFoldRepairs && !stopped(); ++repair) {
      const NewSelfIntersections folds = new_self_intersections(outer, b_.input_pairs, 100000, options_.threads);
      if (folds.pairs == 0) break;
      const double factor = repair < kOuterFoldHalvings ? 0.5 : 0.0;
      b_.band.outer_limit =
          shrink_outer_limit(f_.normalized, b_.band.outer_limit, folds.new_pairs, factor, OuterOffsetLimitOptions{}.slope);
      problem_->set_outer_limit(b_.band.outer_limit);
      ++b_.outer_summary.fold_repairs;
      say_("outer fold repair " + std::to_string(b_.outer_summary.fold_repairs) + ": " + std::to_string(folds.pairs) +
           " face pairs cross, their limits lowered");
      minimize(round);
    }
    return constraints_met;
  }

  // The offset surfaces of an evaluation, input units.
  void surfaces(const ReducedProblem::Evaluation& at, Mesh& inner_surface, Mesh& outer_surface) const {
    inner_surface = input_;
    outer_surface = input_;
    for (Eigen::Index i = 0; i < input_.V.rows(); ++i) {
      inner_surface.V.row(i) += (at.inner_offset(i) / f_.scale) * b_.band.inner_direction.row(i);
      if (options_.outer) outer_surface.V.row(i) += (at.outer_offset(i) / f_.scale) * b_.band.outer_direction.row(i);
    }
  }

  void minimize(int round) {
    fold_prediction_.reset();
    solved = augmented_lagrangian_minimize(problem_->constrained_problem(), x_, params(round));
    total_evaluations += solved.evaluations;
    if (solved.x.size() == x_.size()) x_ = solved.x;  // an invalid problem leaves x where it was
    eval = problem_->evaluate(x_);
    surfaces(eval, inner, outer);
    // A problem the solver refuses (hard bounds with an empty box) or cannot evaluate at the start
    // is not changed by tighter bounds or a correction either.
    const bool refused = solved.status == AlStatus::invalid_input || solved.status == AlStatus::numerical_issue;
    constraints_met = !refused && offsetopt::constraints_met(solved, options_);
  }

  const Mesh& input_;
  const OptimizeOptions& options_;
  const Frame& f_;
  Band& b_;
  const Eigen::MatrixXd& basis_;
  ReducedOptions reduced_options_;
  Progress say_;
  std::unique_ptr<ReducedProblem> problem_;
  Eigen::VectorXd x_;
  std::optional<AlResult> warm_;
  bool corrected_ = false;
  double round_cap_ = 0.0;  // the running correction's cap on its first penalty (0: the options')
  FoldPredictor predict_folds_;
  std::optional<FoldPrediction> fold_prediction_;
};

// Coarse to fine solve: the reduced problem on the coarse copy (its vertices are input vertices,
// so the band is the input's at them, and its basis is the coarse eigenvectors the input's basis
// was carried from). An evaluation there costs 1/30 of one at 10^6 vertices; the solve on the
// input then starts from its end and multipliers and needs fewer evaluations.
std::optional<AlResult> coarse_solve(const OptimizeOptions& options, const Frame& f, const Band& b, const CoarseCopy& coarse,
                                     const Mesh& coarse_mesh, const Eigen::MatrixXd& coarse_basis,
                                     const ReducedOptions& reduced_options, int& evaluations) {
  if (options.k == 0 || options.bounds != BoundsMode::clamp) return std::nullopt;
  const std::vector<int>& kept = coarse.decimated.input_vertex;
  const Eigen::Index m = static_cast<Eigen::Index>(kept.size());
  const OffsetBand& fine = b.band;
  OffsetBand band;
  band.inner_direction.resize(m, 3);
  band.outer_direction.resize(m, 3);
  band.lower.resize(m);
  band.upper.resize(m);
  band.fixed.resize(static_cast<std::size_t>(m));
  if (fine.outer_limit.size()) band.outer_limit.resize(m);
  for (Eigen::Index c = 0; c < m; ++c) {
    const Eigen::Index i = kept[static_cast<std::size_t>(c)];
    band.inner_direction.row(c) = fine.inner_direction.row(i);
    band.outer_direction.row(c) = fine.outer_direction.row(i);
    band.lower(c) = fine.lower(i);
    band.upper(c) = fine.upper(i);
    band.fixed[static_cast<std::size_t>(c)] = fine.fixed[static_cast<std::size_t>(i)];
    if (fine.outer_limit.size()) band.outer_limit(c) = fine.outer_limit(i);
  }
  ReducedProblem problem(coarse_mesh, band, coarse_basis, false, f.goal, reduced_options);
  AlResult solved = augmented_lagrangian_minimize(problem.constrained_problem(), problem.start_point(), options.solver);
  evaluations = solved.evaluations;
  if (solved.status == AlStatus::invalid_input || solved.status == AlStatus::numerical_issue || !solved.x.allFinite())
    return std::nullopt;
  return solved;
}

// Stages "cavity" and "verify": the offset surfaces verified as they are, and, where they do not
// verify (or `--cavity contour`), the contoured cavity corrected in moment space (docs/design.md "The
// written cavity", step 4): the goal is solved again on the offset model's integrals plus the
// difference the contour made, warm-started, until the written solid verifies.
struct Cavity {
  Mesh outer;                  // the outer surface as written (rounded to the output's precision)
  Mesh written;                // the cavity's shells, normals out of the void
  Verification verification;
  CavitySummary summary;
};

// An opening cut through a contoured cavity (cavity/open_cavity.h) for a --fix region: a channel
// for a half-space, a hole to the surface point nearest a sphere region's centre.
bool wants_channel(const OptimizeOptions& options, const Band& b) {
  return b.fixed_count > 0 && options.fix.kind != FixRegion::Kind::none;
}

// Inputs large enough for the coarse copy, with two or more threads: there the stages after the
// solve take seconds, and work started before it is known to be wanted pays for itself (the
// quadric void beside the skeleton, the offset surfaces' verification beside the contour). The
// results are the same either way.
bool large_input(Eigen::Index n) {
  const ContractionOptions defaults;
  return defaults.coarse_above > 0 && n > defaults.coarse_above;
}

bool work_ahead(const OptimizeOptions& options, Eigen::Index n) { return options.threads > 1 && large_input(n); }

// The quadric void started beside the skeleton, the basis and the solve: where work ahead pays,
// and for float, whose offset void almost never competes (the offset model balances the mass and
// stops at the margin: 26 of 26 census meshes floating at 0.8 wrote the quadric void, the offset
// void reaching 5-41% of the possible lowering or missing the goal). On small inputs it takes
// every thread, since the stages beside it end first.
bool quadric_ahead(const OptimizeOptions& options, Eigen::Index n) {
  return work_ahead(options, n) || (options.threads > 1 && options.goal == GoalKind::floating);
}

// The verification of the offset surfaces and the goal's inputs they share with the contour's.
VerifyInput offset_verify_input(const OptimizeOptions& options, const Frame& f, const Band& b, const Mesh& outer,
                                const Mesh& inner, double bound_violation) {
  VerifyInput verify_input = verify_input_for(options, f);
  verify_input.outer = &outer;
  verify_input.inner = &inner;
  verify_input.fixed = b.band.fixed;
  verify_input.bound_violation = bound_violation;
  if (options.outer) verify_input.outer_own_pairs = &b.input_pairs;
  return verify_input;
}

// Whether the offset path contours a cavity once the offset surfaces' verification is known.
bool wants_offset_contour(const OptimizeOptions& options, const Cavity& c) {
  const bool offset_verified = verified(c.verification);
  return options.cavity == CavityMode::contour ||
         (options.cavity == CavityMode::automatic && (!offset_verified || options.wants_drain_holes()));
}

void contour_offset_void(const OptimizeOptions& options, const Frame& f, const Band& b, OffsetSolve& solve,
                         StageTimings& timings, const Progress& say, const Vector10d& opening_void, Cavity& c);

// The offset surfaces `outer` and `inner` verified as they are and, where they pass, as rounded
// for the output: the cavity they make, its summary's offset fields, and the seconds it took.
Cavity verify_offset_surfaces(const OptimizeOptions& options, const Frame& f, const Band& b, const Mesh& outer,
                              const Mesh& inner, double bound_violation, double& seconds, bool goal_only = false) {
  const auto start = Clock::now();
  Cavity c;
  VerifyInput verify_input = offset_verify_input(options, f, b, outer, inner, bound_violation);
  verify_input.goal_only = goal_only;
  const auto& tick = options.on_stage_progress;
  if (tick) tick("verify", -1.0);
  // The wall's per-vertex bounds, for the check of the rounded surfaces: they move each distance
  // by at most the rounding's margin, so only the vertices near the thinnest are searched again.
  std::vector<double> wall_lower;
  const bool rounded_check = options.output_precision != StoredPrecision::exact;
  if (rounded_check) verify_input.wall_bounds.record = &wall_lower;
  c.verification = verify_offsets(verify_input);
  // As written: rounded to the output's precision and verified again (only when it can pass:
  // on real meshes the offset surface rarely verifies even unrounded).
  RoundedForOutput offset_written;
  if (rounded_check && verified(c.verification)) {
    offset_written = round_for_output(outer, inner, b.band.fixed, options.output_precision, options.threads);
    verify_input.outer = &offset_written.outer;
    verify_input.inner = &offset_written.inner;
    verify_input.rounding = &offset_written;
    const double largest = std::max(outer.V.size() ? outer.V.cwiseAbs().maxCoeff() : 0.0,
                                    inner.V.size() ? inner.V.cwiseAbs().maxCoeff() : 0.0);
    verify_input.wall_bounds = WallBounds{&wall_lower, rounding_wall_margin(largest, options.output_precision), nullptr};
    c.verification = verify_offsets(verify_input);
  } else {
    offset_written.outer = outer;
    offset_written.inner = inner;
  }
  seconds = seconds_since(start);
  if (tick) tick("verify", 1.0);
  c.summary.mode = options.cavity;
  c.summary.offset_goal_met = c.verification.goal_met;
  if (!goal_only) c.summary.offset_valid = c.verification.valid;
  c.summary.offset_failures = c.verification.failures;
  c.outer = offset_written.outer;
  c.written = offset_written.inner;
  return c;
}

// `opening_void`: the integrals (frame) the openings cut beyond the cavity, added to every
// correction's Δ (the openings stage solves again with them, optimize_offsets).
// `contour`: false leaves the contour to the caller (contour_offset_void), which may not need it,
// and then `goal_only` checks the offset surfaces' goal alone (their validity cannot change the
// choice, make_cavity).
// `alongside`: the offset surfaces are verified on another thread while the contour is made (on
// large inputs they almost never verify; when they do, the contour is dropped): the same result.
Cavity make_offset_cavity(const OptimizeOptions& options, const Frame& f, const Band& b, OffsetSolve& solve,
                          StageTimings& timings, const Progress& say, const Vector10d& opening_void = Vector10d::Zero(),
                          bool contour = true, bool alongside = false, bool goal_only = false) {
  // Handed off for folds, the inner surface winds around some grid nodes neither once nor not at
  // all, which a closed surface that keeps clear of itself never does: the offset surfaces are
  // not written as they are, whatever a search for their defects would find, and only their goal
  // is checked, for the report (on the demo bottle standing filled with --outer the search cost
  // 0.15 G instructions, on the way to the contour).
  const std::int64_t folded = contour ? solve.handed_off_folded_nodes() : 0;
  if (!contour || !alongside || b.fixed_count > 0 || options.outer || options.cavity == CavityMode::offset || folded > 0) {
    Cavity c = verify_offset_surfaces(options, f, b, solve.outer, solve.inner, solve.bound_violation(), timings.verify,
                                      (goal_only && !contour) || folded > 0);
    if (folded > 0) {
      c.verification.valid = false;
      c.verification.failures.push_back("the inner surface folds: its winding number is neither 0 nor 1 at " + std::to_string(folded) +
                                        " nodes of the contour's grid (not searched for other defects)");
      c.summary.offset_valid = false;
      c.summary.offset_failures = c.verification.failures;
    }
    if (contour) contour_offset_void(options, f, b, solve, timings, say, opening_void, c);
    return c;
  }
  // The contour's corrections solve again and move solve's surfaces: the task verifies copies,
  // and the first solve is kept to be put back if the contour is not wanted.
  OffsetSolve::State first = solve.state();
  const double bound_violation = solve.bound_violation();
  double verify_seconds = 0.0;
  std::future<Cavity> verified = start_task(true, [&options, &f, &b, &first, bound_violation, &verify_seconds]() {
    return verify_offset_surfaces(options, f, b, first.outer, first.inner, bound_violation, verify_seconds);
  });
  Cavity contoured;  // verification.goal_met false: the contour is wanted
  std::vector<std::string> lines;  // its progress, said once it is known to be wanted
  contour_offset_void(options, f, b, solve, timings, [&lines](const std::string& line) { lines.push_back(line); },
                      opening_void, contoured);
  Cavity c = verified.get();
  timings.verify = verify_seconds;
  if (!wants_offset_contour(options, c)) {
    timings.contour.reset();
    timings.correct.reset();
    solve.restore_uncorrected(std::move(first));
    return c;
  }
  for (const std::string& line : lines) say(line);
  // A contour that failed before its first round reads the offset surfaces' verification: made
  // again in order (nothing was corrected yet).
  if (!contoured.summary.rounds || contoured.summary.rounds->empty()) {
    contour_offset_void(options, f, b, solve, timings, say, opening_void, c);
    return c;
  }
  c.verification = std::move(contoured.verification);
  c.outer = std::move(contoured.outer);
  c.written = std::move(contoured.written);
  c.summary.rounds = std::move(contoured.summary.rounds);
  c.summary.written = contoured.summary.written;
  return c;
}

// Folds before the first contour (cavity/fold_integrals.h): where the inner offset surface turns
// pockets inside out, the first contour's void differs from the model's by the folds' integrals
// and the wall's cut. When the model plus both misses a margin row, so would that contour (the
// demo bottle standing filled with --outer: 2.5e-4 predicted, 2.2e-4 contoured), and the
// correction it would cause is made first, from them, which saves a contour. The wall's cut costs
// a distance query per node and is read only when the folds alone predict a miss. Equality rows
// are left to the rounds: their tolerances are the verification's, which the folds rarely cross
// (the demo top 6e-6, the roly-poly 3e-5, against 1e-4). Only for a solve not corrected yet: a
// correction's shift is a contour's measure, better than this one. Returns the winding numbers
// the first contour reads when the surface did not move; counts the correction in `corrections`.
std::optional<FoldIntegrals> correct_for_folds(const OptimizeOptions& options, const Frame& f, const Band& b, OffsetSolve& solve,
                                               const ContourCavityOptions& cavity_options, const Vector10d& opening_void,
                                               const Progress& say, Cavity& c, int& corrections) {
  if (!solve.constraints_met || solve.corrected() || options.max_correction_rounds < 1) return std::nullopt;
  // The first solve handed off for these folds: the prediction it was made on (no openings yet).
  std::optional<FoldPrediction> handed = solve.take_fold_prediction();
  FoldPrediction p = handed && opening_void.isZero()
                         ? std::move(*handed)
                         : predict_folds(options, f, b, solve.outer, solve.inner, solve.eval, cavity_options, opening_void);
  if (!p.folds.ok) return std::nullopt;
  if (!p.miss) return std::move(p.folds);
  c.summary.fold_correction = FoldCorrection{p.folds.volume, p.cut->volume, p.predicted};
  say("folds: the inner offset surface folds over " + format_double(p.folds.volume) + " of void and the wall cuts " +
      format_double(-p.cut->volume) + "; with them a margin row misses by " + format_double(p.predicted) + " (frame): corrected" +
      (handed ? " from the solve's first iterate within " + format_double(kFoldHandOffViolation) : std::string()) +
      " before contouring");
  solve.correct(p.shift, ++corrections, kFoldCorrectionPenaltyCap);
  return std::nullopt;
}

// The contoured cavity of the offset path, where the offset surfaces did not verify (or it is asked
// for): corrected until the written solid verifies. `c` holds the offset surfaces' verification.
void contour_offset_void(const OptimizeOptions& options, const Frame& f, const Band& b, OffsetSolve& solve,
                         StageTimings& timings, const Progress& say, const Vector10d& opening_void, Cavity& c) {
  const VerifyInput verify_input = offset_verify_input(options, f, b, solve.outer, solve.inner, solve.bound_violation());
  const auto& tick = options.on_stage_progress;
  const bool want_contour = wants_offset_contour(options, c);
  std::string problem;
  if (want_contour) {
    const auto stage_start = Clock::now();
    const ContourCavityOptions cavity_options = offset_contour_options(options, f, solve.outer);
    std::vector<ContourRound>& rounds = c.summary.rounds.emplace();
    double contour_seconds = 0.0;
    int corrections = 0;
    const std::optional<FoldIntegrals> folds = correct_for_folds(options, f, b, solve, cavity_options, opening_void, say, c, corrections);
    for (int round = 0;; ++round) {
      // Most runs need one or two rounds; the estimate is the round over the rounds allowed.
      if (tick) tick("contour", static_cast<double>(round) / (options.max_correction_rounds + 1));
      const auto contour_start = Clock::now();
      const TriangleBvh outer_offset_bvh = options.outer ? TriangleBvh(solve.outer.V, solve.outer.F) : TriangleBvh();
      const ContourCavity contoured = contour_cavity(solve.outer, options.outer ? outer_offset_bvh : *b.bvh, solve.inner,
                                                     cavity_options, round == 0 && folds ? &folds->inner : nullptr);
      contour_seconds += seconds_since(contour_start);
      if (!contoured.ok) {
        problem = "the cavity could not be contoured: " + contoured.message;
        break;
      }
      // The contour's integrals in the frame beside the goal's check, which sums them again from
      // another origin: each reads the cavity alone and is one sum in face order, so the same bits.
      std::future<Vector10d> contoured_integrals =
          start_task(options.threads > 1, [&f, &contoured] { return integrals_in_frame(f, contoured.cavity); });
      VerifyInput contour_input = verify_input;
      contour_input.outer = &solve.outer;
      contour_input.inner = &contoured.cavity;
      contour_input.rounding = nullptr;
      contour_input.fixed.clear();
      contour_input.bound_violation = 0.0;  // the band bounds the offset model, not the contour
      // The goal first: a contour whose goal is missed and that a correction will replace needs
      // no validity search (on a 10^5-face cavity the costliest part of a round).
      contour_input.goal_only = true;
      c.verification = verify_offsets(contour_input);
      const Vector10d delta = contoured_integrals.get() - solve.eval.inner_integrals;
      const bool will_correct = !c.verification.goal_met && solve.constraints_met && corrections < options.max_correction_rounds;
      VerifiedCavity written;
      if (!will_correct) {
        written = verify_written_cavity(contour_input, solve.outer, contoured.cavity, contoured.faces_below_wall,
                                        options.output_precision);
        c.verification = written.verification;
      }
      const double cube = f.scale * f.scale * f.scale;
      ContourRound& entry = rounds.emplace_back(contour_round(contoured, c.verification, !will_correct));
      entry.delta_in_frame = delta;
      entry.void_volume_offset = solve.eval.inner_integrals(kIntVolume) / cube;
      entry.void_volume_contour = (solve.eval.inner_integrals(kIntVolume) + delta(kIntVolume)) / cube;
      say("cavity round " + std::to_string(round) + ": " + std::to_string(contoured.active_cells) + " cells contoured, " +
          std::to_string(contoured.shells) + " shells, goal " + (c.verification.goal_met ? "met" : "not met") + ", " +
          (will_correct ? "corrected next" : c.verification.valid ? "valid" : "not valid"));
      c.outer = will_correct ? solve.outer : written.rounded.outer;
      c.written = will_correct ? contoured.cavity : written.rounded.inner;
      // Stops at a verified contour, an invalid one (a correction cannot mend it), a goal whose
      // constraints the solver could not meet, or the last round.
      if (!will_correct) break;
      solve.correct(delta + opening_void, ++corrections);
    }
    if (tick) tick("contour", 1.0);
    timings.contour = contour_seconds;
    timings.correct = seconds_since(stage_start) - contour_seconds;
  }
  if (want_contour && problem.empty()) c.summary.written = WrittenCavity::contour;
  if (!problem.empty()) {
    c.verification.valid = false;
    c.verification.failures.insert(c.verification.failures.begin(), problem);
  }
}

// The goals that lower the centre of mass: their voids are measured against the best (optimality),
// and the quadric void may replace an offset void that falls short of it.
bool lowers_centre(GoalKind kind) {
  return kind == GoalKind::stand || kind == GoalKind::stand_filled || kind == GoalKind::roly_poly ||
         kind == GoalKind::floating;
}

// The goals the quadric void is written for: those, spin, whose programme's optimum leaves the
// solid's ∫z least at the lowest level it reaches, and volume, whose is a ball clipped to the
// carvable cells (cavity/reachability.h). Their voids are written only where the offset void misses
// the goal: no measure says how far from the best a spinning void is, and a volume is met or not
// (the offset void cannot hold less than the part of the band the skeleton's gap keeps: on the
// demo sphere 2,965 of its 113,000, so `--target-volume 1000` exited 3).
bool quadric_goal(GoalKind kind) { return lowers_centre(kind) || kind == GoalKind::spin || kind == GoalKind::volume; }

// The goal's objective on the solid as written (normalised frame), or for float the depth under
// the centre of buoyancy negated: smaller is better either way.
double written_score(const Frame& f, const Mesh& outer, const Mesh& cavity, const Verification& v) {
  if (f.goal.kind == GoalKind::floating) return -v.goal.com_below_buoyancy * f.scale;
  return evaluate_goal(f.goal, integrals_in_frame(f, outer), integrals_in_frame(f, cavity)).objective;
}

std::optional<Optimality> optimality(const Frame& f, const Reachability& reach, const Verification& v) {
  // An invalid solid (a wall below the request) may carve past what any valid void reaches.
  if (!v.goal_met || !v.valid || !reach.reachable) return std::nullopt;
  Optimality o;
  if (f.goal.kind == GoalKind::floating) {
    if (!reach.best_margin || !(*reach.best_margin > 0.0)) return std::nullopt;
    o.before = 0.0;  // a solid body's centre of mass is its centre of buoyancy
    o.written = v.goal.com_below_buoyancy;
    o.best = *reach.best_margin;
    o.fraction = o.written / o.best;
    return o;
  }
  if (!reach.lowest_cz) return std::nullopt;
  o.before = f.before(kCz) - f.zmin;
  o.written = v.goal.center_of_mass.z() - f.zmin;
  o.best = *reach.lowest_cz;
  if (!(o.before - o.best > 0.0)) return std::nullopt;
  o.fraction = (o.before - o.written) / (o.before - o.best);
  return o;
}

// The margin the verified solid reaches, in the programme's terms (optimize/reachability_stage.h):
// inside the support polygon, the filled object's too for stand-filled; below the sphere centre;
// below the centre of buoyancy. None for spin and volume.
std::optional<double> written_margin(GoalKind kind, const GoalFigures& g) {
  switch (kind) {
    case GoalKind::stand: return g.empty.com_margin;
    case GoalKind::stand_filled: return std::min(g.empty.com_margin, g.filled.com_margin);
    case GoalKind::roly_poly: return g.com_below_center;
    case GoalKind::floating: return g.com_below_buoyancy;
    case GoalKind::spin:
    case GoalKind::volume: break;
  }
  return std::nullopt;
}

// A verified solid that meets the goal is a void that reaches it, whatever the programme found:
// with --outer its mid reading has no shaving and can fall short of what the thickened solid
// does (the bottle standing filled: -4.3 against 0.60 written), and an undecided programme has
// no answer. A refusal's certificate is never overruled: the run stops before the solve.
void credit_written_solid(ReachabilitySummary& reach, GoalKind kind, const Verification& v) {
  if (reach.reachable || (reach.decided && reach.evidence == "certificate")) return;
  reach.reachable = reach.decided = true;
  reach.evidence = "written solid";
  const std::optional<double> margin = written_margin(kind, v.goal);
  if (margin && (!reach.best_margin || *margin > *reach.best_margin)) reach.best_margin = margin;
}

// The fraction of the possible lowering the offset model's solution predicts (its integrals, before
// any contour), as optimality() reads it of a written solid: for float, the depth of the centre of
// mass below the centre of buoyancy, which the model takes fully submerged (shape/goal.h: its mass
// row balances the whole outer volume), so the centre of buoyancy is the outer surface's centroid.
std::optional<double> predicted_fraction(const Frame& f, const Reachability& reach, const ReducedProblem::Evaluation& e) {
  const double shell_volume = e.outer_integrals(kIntVolume) - e.inner_integrals(kIntVolume);
  if (!(shell_volume > 0.0)) return std::nullopt;
  const double shell_z = (e.outer_integrals(kIntZ) - e.inner_integrals(kIntZ)) / shell_volume;
  if (f.goal.kind == GoalKind::floating) {
    if (!reach.best_margin || !(*reach.best_margin > 0.0) || !(e.outer_integrals(kIntVolume) > 0.0)) return std::nullopt;
    const double buoyancy_z = e.outer_integrals(kIntZ) / e.outer_integrals(kIntVolume);
    return (buoyancy_z - shell_z) / f.scale / *reach.best_margin;
  }
  if (!reach.lowest_cz) return std::nullopt;
  const double cz = shell_z / f.scale + f.origin.z() - f.zmin;
  const double before = f.before(kCz) - f.zmin, best = *reach.lowest_cz;
  if (!(before - best > 0.0)) return std::nullopt;
  return (before - cz) / (before - best);
}

// "97%": a fraction for a one-line reason.
std::string percent(double fraction) {
  char text[32];
  std::snprintf(text, sizeof text, "%.0f%%", fraction * 100.0);
  return text;
}

// Whether a quadric void can be written for the goal. Its moment rows read a void inside a fixed
// outer surface with nothing cut through it; a volume's one row reads the void alone, so a volume
// takes it inside the outer surface the solve thickened (--outer) and opened by the channel of a
// --fix region (cut_openings aims the void at the target less the channel's share).
bool quadric_writable(const OptimizeOptions& options, const Band& b) {
  if (!quadric_goal(options.goal)) return false;
  if (options.goal == GoalKind::volume) return b.fixed_count == 0 || wants_channel(options, b);
  return !options.outer && b.fixed_count == 0;
}

// The quadric void and, where it is thin, the one contoured twice as fine: what make_cavity writes
// when the offset void falls short. It reads the input (the outer surface: no --outer), its tree,
// the frame and the programme, nothing the skeleton or the solve make, so it can be computed
// alongside them (QuadricAhead).
struct QuadricAttempt {
  QuadricVoid q;
  std::optional<Optimality> optimality;
  double seconds = 0.0;
};

QuadricAttempt attempt_quadric(const OptimizeOptions& options, const Frame& f, const Mesh& outer, const TriangleBvh& outer_bvh,
                               const Reachability& programme, int threads,
                               const std::vector<std::pair<int, int>>* outer_own_pairs = nullptr) {
  const auto start = Clock::now();
  QuadricVoidInput in;
  in.outer = &outer;
  in.outer_bvh = &outer_bvh;
  in.start = *programme.optimum;
  in.programme = &programme;
  in.goal_in_frame = f.goal;
  in.origin = f.origin;
  in.diagonal = f.diag;
  // The wall survives the rounding of both surfaces to the output's precision.
  in.contour.wall = f.wall + rounding_wall_margin(outer.V.size() ? outer.V.cwiseAbs().maxCoeff() : 0.0, options.output_precision);
  in.contour.cells_per_wall = options.cavity_cells_per_wall;
  in.contour.margin_cells = options.cavity_margin_cells;
  in.contour.threads = threads;
  in.verify = verify_input_for(options, f);
  in.verify.threads = threads;
  in.verify.outer = &outer;
  in.verify.outer_own_pairs = outer_own_pairs;
  in.max_rounds = options.max_correction_rounds;
  in.headroom = kCorrectionHeadroom;
  QuadricAttempt a;
  a.q = write_quadric_void(in);
  a.optimality = optimality(f, programme, a.q.verification);
  // Where the void is thin (blades, plates), a contour a wall / 1.5 fine loses much of the
  // lowering the programme's cells reach (cgal-data_turbine: 84% of it; 97% on a grid twice as fine),
  // and its integrals jump as parts of it appear and vanish under the wall, more than a float's
  // balance allows (the turbine floating at 0.8, written as PLY: 1% off after six rounds at
  // wall / 1.5, verified at wall / 3). So a grid twice as fine is tried there too.
  const bool missed = !verified(a.q.verification);
  if ((missed || (a.optimality && a.optimality->fraction < options.quadric_below_fraction)) &&
      2.0 * in.contour.cells_per_wall <= kFinestQuadricCellsPerWall) {
    in.contour.cells_per_wall *= 2.0;
    QuadricVoid finer = write_quadric_void(in);
    const std::optional<Optimality> finer_optimality = optimality(f, programme, finer.verification);
    if (missed ? verified(finer.verification) : finer_optimality && finer_optimality->fraction > a.optimality->fraction) {
      a.q = std::move(finer);
      a.optimality = finer_optimality;
    }
  }
  a.seconds = seconds_since(start);
  return a;
}

// The quadric void started before it is known to be wanted (optimize_offsets); make_cavity takes
// it when it wants the quadric void, and otherwise its result is dropped: the same bits either way.
using QuadricAhead = std::future<QuadricAttempt>;

// The quadric void may be written: a goal that lowers the centre of mass, no outer surface or
// fixed region, and a programme that found its optimum.
bool quadric_possible(const OptimizeOptions& options, const ReachabilitySummary& reach) {
  return (options.cavity == CavityMode::automatic || options.cavity == CavityMode::quadric) &&
         lowers_centre(options.goal) && !options.outer && options.fix.kind == FixRegion::Kind::none && reach.programme &&
         reach.programme->reachable && reach.programme->optimum;
}

QuadricAttempt take_quadric(const OptimizeOptions& options, const Frame& f, const Band& b, const OffsetSolve& solve,
                            const Reachability& programme, QuadricAhead* ahead) {
  if (ahead && ahead->valid()) return ahead->get();
  // With --outer (a volume: quadric_writable) the void is contoured a wall inside the outer
  // surface the solve chose, which is searched for new self-intersections as the offset path's is.
  std::optional<TriangleBvh> outer_offset_bvh;
  if (options.outer) outer_offset_bvh.emplace(solve.outer.V, solve.outer.F);
  const TriangleBvh& outer_bvh = outer_offset_bvh ? *outer_offset_bvh : *b.bvh;
  const std::vector<std::pair<int, int>>* own_pairs = options.outer ? &b.input_pairs : nullptr;
  if (programme.optimum || !programme.find_optimum)
    return attempt_quadric(options, f, solve.outer, outer_bvh, programme, options.threads, own_pairs);
  // Spin's or volume's optimum, found now that it is wanted.
  Reachability found = programme;
  programme.find_optimum(found);
  if (!found.optimum) {
    QuadricAttempt none;
    none.q.message = "the reachability programme found no optimal void";
    return none;
  }
  return attempt_quadric(options, f, solve.outer, outer_bvh, found, options.threads, own_pairs);
}

// The offset path's cavity `c` against the quadric void: the quadric void is made where the offset
// void misses a goal some void reaches or falls short of the best by more than
// options.quadric_below_fraction, and written when it verifies and lowers the centre more or beats
// the offset void's score by more than options.quadric_tie, or when asked for. `attempt`: the
// quadric void when already made.
Cavity choose_cavity(const OptimizeOptions& options, const Frame& f, const Band& b, const OffsetSolve& solve,
                     const Reachability& programme, Cavity c, std::optional<QuadricAttempt> attempt, StageTimings& timings,
                     const Progress& say, QuadricAhead* ahead) {
  const bool forced = options.cavity == CavityMode::quadric;
  auto refuse = [&](const std::string& why) {
    c.verification.valid = false;
    c.verification.failures.insert(c.verification.failures.begin(), why);
  };
  const bool offset_verified = !forced && verified(c.verification);
  if (offset_verified) c.summary.offset_objective = written_score(f, solve.outer, c.written, c.verification);
  const std::optional<Optimality> offset_optimality = optimality(f, programme, c.verification);
  const bool short_of_best =
      lowers_centre(f.goal.kind) && (!offset_optimality || offset_optimality->fraction < options.quadric_below_fraction);
  if (!forced && !(options.cavity == CavityMode::automatic && (!offset_verified || short_of_best))) return c;

  if (!attempt) attempt = take_quadric(options, f, b, solve, programme, ahead);
  const QuadricVoid& q = attempt->q;
  const std::optional<Optimality>& quadric_optimality = attempt->optimality;
  timings.quadric = attempt->seconds;
  c.summary.quadric_rounds = q.rounds;
  const bool quadric_verified = verified(q.verification);
  say(std::string("quadric void: ") + std::to_string(q.rounds.size()) + " contours, " +
      (quadric_verified ? "verified" : q.message.empty() ? "not verified" : q.message));
  if (quadric_verified) c.summary.quadric_objective = written_score(f, solve.outer, q.written, q.verification);
  // The lowering comes first: an offset void short of the best by more than
  // quadric_below_fraction gives way to a quadric void that lowers the centre more; the goal's
  // objective decides between voids that both lower it well (or both fall short by as much).
  const bool lowers_more = offset_verified && short_of_best && offset_optimality && quadric_optimality &&
                           quadric_optimality->fraction > offset_optimality->fraction;
  const bool better_objective =
      offset_verified && quadric_verified &&
      *c.summary.offset_objective - *c.summary.quadric_objective > options.quadric_tie * std::fabs(*c.summary.quadric_objective);
  const bool take = forced ? q.written.F.rows() > 0 : quadric_verified && (!offset_verified || lowers_more || better_objective);
  if (take) {
    c.outer = q.outer;
    c.written = q.written;
    c.verification = q.verification;
    c.summary.written = WrittenCavity::quadric;
    c.summary.choice = forced ? "asked for (--cavity quadric)"
                       : !offset_verified ? "the offset void misses a goal the quadric void reaches"
                       : lowers_more ? "the offset void reaches " + percent(offset_optimality->fraction) +
                                           " of the possible lowering, the quadric void " + percent(quadric_optimality->fraction)
                                     : "the quadric void's objective is better by more than " +
                                           format_double(options.quadric_tie * 100.0) + "%";
    if (forced && !q.message.empty()) refuse(q.message);
  } else if (forced) {
    refuse("no quadric void was written: " + (q.message.empty() ? std::string("unknown") : q.message));
  } else {
    c.summary.choice = !quadric_verified ? "the quadric void did not verify: " +
                                               (q.message.empty() ? (q.verification.failures.empty() ? std::string("unknown")
                                                                                                    : q.verification.failures.front())
                                                                  : q.message)
                                         : *c.summary.offset_objective <= *c.summary.quadric_objective
                                               ? std::string("the offset void's objective is the better one")
                                               : "the offset void is within " + format_double(options.quadric_tie * 100.0) +
                                                     "% of the quadric void's objective";
  }
  return c;
}

// Stages "cavity" and "verify" with the quadric void: the offset path (make_offset_cavity), then
// the choice against the quadric void (choose_cavity). A contour lowers the centre less than its
// model, and its objective is no better (the census, 76 meshes: every model predicted more of the
// possible lowering than its contour reached, by 0.001 to 0.35, and its objective was below the
// contour's but for kContourBelowModel), so the model's figures stand for the contour's where they
// already settle the choice.
Cavity make_cavity(const OptimizeOptions& options, const Frame& f, const Band& b, OffsetSolve& solve,
                   const ReachabilitySummary& reach, StageTimings& timings, const Progress& say, QuadricAhead* ahead) {
  const bool forced = options.cavity == CavityMode::quadric;
  const bool writable = quadric_writable(options, b);
  const bool wanted = options.cavity == CavityMode::automatic || forced;
  const bool possible = wanted && writable && reach.programme && reach.programme->reachable &&
                        (reach.programme->optimum || reach.programme->find_optimum);
  double predicted = std::numeric_limits<double>::infinity();  // none: the offset path as always
  if (possible && options.cavity == CavityMode::automatic && !options.wants_drain_holes())
    predicted = predicted_fraction(f, *reach.programme, solve.eval).value_or(predicted);
  // The quadric void first: where the model predicts the offset void short of the best, or on a
  // large input (where it is started ahead with two or more threads; on one it is made here, so the
  // report is the same). The offset void's contour is then left out when the quadric void
  // verifies, beats the prediction, and the offset void could not be written instead: it would
  // reach less than quadric_below_fraction, or the model's own objective (which its contour does
  // not beat) is already worse than the quadric void's by more than quadric_tie.
  std::optional<QuadricAttempt> early;
  std::string skipped_because;
  if (std::isfinite(predicted) && (predicted < options.quadric_first_below || large_input(solve.outer.V.rows()))) {
    early = take_quadric(options, f, b, solve, *reach.programme, ahead);
    const QuadricVoid& q = early->q;
    // A margin over the prediction: offset surfaces that verified would reach it up to their rounding.
    if (verified(q.verification) && early->optimality &&
        early->optimality->fraction > predicted + kContourBelowModel) {
      const double quadric_objective = written_score(f, solve.outer, q.written, q.verification);
      const std::string reaches = ", the quadric void reaches " + percent(early->optimality->fraction);
      if (predicted < options.quadric_first_below)
        skipped_because = (solve.constraints_met ? "the offset model predicts " + percent(predicted) + " of the possible lowering"
                                                 : std::string("the offset model misses the goal")) + reaches;
      else if (solve.eval.objective * (1.0 - kContourBelowModel) - quadric_objective > options.quadric_tie * std::fabs(quadric_objective))
        skipped_because = "the offset model's objective is worse than the quadric void's by more than " +
                          format_double(options.quadric_tie * 100.0) + "%" + reaches;
    }
  }
  // Where the contour is left out, the offset surfaces' validity cannot change the choice either
  // (were they valid, they would reach the prediction and the model's objective): their goal alone
  // is checked, and the report says their validity was not searched.
  Cavity c = make_offset_cavity(options, f, b, solve, timings, say, Vector10d::Zero(), skipped_because.empty(),
                                work_ahead(options, solve.outer.V.rows()), !skipped_because.empty());
  if (!possible) {
    if (forced) {
      c.verification.valid = false;
      c.verification.failures.insert(
          c.verification.failures.begin(),
          !writable           ? "--cavity quadric needs a goal that lowers the centre of mass or spin, without --outer or --fix, or a volume"
          : !reach.programme ? "no quadric void: the reachability programme could not be set up"
                             : "no quadric void: no void the programme knows reaches the goal");
    }
    return c;
  }
  // Offset surfaces that verify need no contour: they are judged as always.
  if (skipped_because.empty() || !wants_offset_contour(options, c))
    return choose_cavity(options, f, b, solve, *reach.programme, std::move(c), std::move(early), timings, say, ahead);
  const QuadricVoid& q = early->q;
  timings.quadric = early->seconds;
  say("quadric void: " + std::to_string(q.rounds.size()) + " contours, verified, the offset void not contoured");
  c.summary.quadric_rounds = q.rounds;
  c.summary.quadric_objective = written_score(f, solve.outer, q.written, q.verification);
  c.outer = q.outer;
  c.written = q.written;
  c.verification = q.verification;
  c.summary.written = WrittenCavity::quadric;
  c.summary.choice = skipped_because + "; the offset void was not contoured";
  return c;
}

// The quadric void holding a volume, aimed at `aim` (normalised frame) instead of the target, and
// verified against that aim to a quarter of the error the target allows: the openings' channels
// add the rest of the volume and their own error. Checked to the target's 1e-4 itself, the void's
// error alone could use it all up (the demo sphere behind z>5 at 300: the aimed voids within
// 0.9e-4 of their aims, the opened ones 2.0e-4 and 2.7e-4 off the target, six aims). None when it
// does not verify.
std::optional<QuadricAttempt> quadric_void_aimed_at(const OptimizeOptions& options, const Frame& f, const Band& b,
                                                    const OffsetSolve& solve, const Reachability& programme, double aim) {
  Frame aimed = f;
  aimed.goal.target_volume = aim;
  aimed.goal_input.target_volume = aim / (f.scale * f.scale * f.scale);
  aimed.volume_tolerance = std::min(f.volume_tolerance, 0.25 * f.volume_tolerance * f.goal.target_volume / aim);
  QuadricAttempt a = take_quadric(options, aimed, b, solve, programme, nullptr);
  if (!verified(a.q.verification)) return std::nullopt;
  return a;
}

// Stage "openings": drain holes and the channel cut through the written cavity and verified on the
// cut solid as written (cavity/verify_opened_cavity.h). When the openings' material moves the goal
// out of reach, the goal is solved again with their integrals added to the last contour's Δ and
// the cavity contoured again, or a quadric void holding a volume is aimed at the target less the
// openings' (at most 6 times: the channel changes as the void shrinks; on the demo sphere behind
// --fix 'z>5' a target of 300 takes three).
OpeningsSummary cut_openings(const OptimizeOptions& options, const Frame& f, const Band& b, OffsetSolve& solve,
                             const Reachability* programme, Cavity& cavity, std::optional<Mesh>& opened_solid,
                             StageTimings& timings, const Progress& say) {
  const auto start = Clock::now();
  OpenCavityOptions open_options;
  open_options.holes = options.drain_holes;
  open_options.auto_holes = options.drain_holes_auto;
  // PrusaSlicer's 2 mm (input units read as millimetres), but at most 2% of the diagonal: a model
  // in metres or inches gets a hole in proportion to it.
  open_options.hole_radius = options.drain_hole_radius > 0.0 ? options.drain_hole_radius : std::min(2.0, 0.02 * f.diag);
  if (wants_channel(options, b)) open_options.opening = options.fix;
  open_options.wall = f.wall;
  const VerifyInput base = verify_input_for(options, f);
  OpeningsSummary summary;
  double aim = f.goal.target_volume;                  // a quadric void's volume aimed at (below)
  std::optional<std::pair<double, double>> previous;  // the last aim and its miss
  for (int attempt = 0;; ++attempt) {
    if (!cavity.verification.valid) {
      summary.message = "the cavity was not valid before the openings";
      break;
    }
    VerifiedOpenedCavity v =
        verify_opened_cavity(cavity.outer, cavity.written, open_options, base, cavity.verification, options.output_precision);
    ++summary.rounds;
    summary.openings = v.opened.openings;
    summary.cavity_shells = v.opened.cavity_shells;
    summary.spill_height = v.opened.spill_height;
    summary.void_volume = v.void_volume;
    summary.liquid_volume = v.liquid ? std::optional<double>(v.liquid_volume) : std::nullopt;
    summary.closed = v.closed;
    summary.new_pairs = v.new_pairs;
    summary.chips_dropped = v.opened.chips_dropped;
    summary.message = v.opened.ok ? "" : v.opened.message;
    say("openings " + std::to_string(attempt) + ": " + std::to_string(v.opened.openings.size()) + " cut, goal " +
        (v.verification.goal_met ? "met" : "not met") + ", " + (v.verification.valid ? "valid" : "not valid"));
    const bool correctable = cavity.summary.written == WrittenCavity::contour && cavity.summary.rounds &&
                             !cavity.summary.rounds->empty() && solve.constraints_met && v.opened.ok &&
                             v.verification.valid && !v.verification.goal_met && attempt < 3;
    // A quadric void holding a volume: the openings' channels are part of the void (on the demo
    // sphere a 2 mm drain hole added 297 to a target of 1000), so the void is aimed lower, by a
    // secant on what the opened void would miss by were the void exactly at its aim (so the void's
    // own error, up to its tolerance, is not read as the channels' change). A drain hole lengthens
    // steadily as the ball shrinks, and the secant follows it; a channel through a --fix region
    // changes in steps (the demo sphere behind z>5 at 300: 75.5, then 47.95 and 47.90 in the
    // frame's 10⁻⁶), which a secant reads as slopes above 1 (1.36: six aims). The channels only
    // grow as the void shrinks, so the slope is kept in [0.5, 1]: at 1, the next aim is the target
    // less the last channels.
    const bool reaimable = cavity.summary.written == WrittenCavity::quadric && f.goal.kind == GoalKind::volume && programme &&
                           v.opened.ok && v.verification.valid && !v.verification.goal_met && attempt < 6;
    std::optional<QuadricAttempt> reaimed;
    if (reaimable) {
      const double channels = integrals_in_frame(f, v.void_surfaces)(kIntVolume) - integrals_in_frame(f, cavity.written)(kIntVolume);
      const double miss = aim + channels - f.goal.target_volume;
      double slope = 1.0;  // of the miss against the aim: 1 + d(channels)/d(aim)
      if (previous && aim != previous->first)
        slope = std::clamp((miss - previous->second) / (aim - previous->first), 0.5, 1.0);
      previous = std::make_pair(aim, miss);
      aim -= miss / slope;
      if (aim > 0.0) reaimed = quadric_void_aimed_at(options, f, b, solve, *programme, aim);
      else
        v.verification.failures.insert(v.verification.failures.begin(),
                                       "the openings' channels alone hold " + format_double(channels / (f.scale * f.scale * f.scale)) +
                                           " of the void, more than the target " + format_double(f.goal_input.target_volume));
    }
    if (reaimed) {
      timings.quadric = timings.quadric.value_or(0.0) + reaimed->seconds;
      cavity.outer = std::move(reaimed->q.outer);
      cavity.written = std::move(reaimed->q.written);
      cavity.verification = std::move(reaimed->q.verification);
      cavity.summary.quadric_rounds = std::move(reaimed->q.rounds);
      continue;
    }
    if (!correctable) {
      cavity.verification = v.verification;
      if (v.opened.ok) opened_solid = std::move(v.solid);
      break;
    }
    const Vector10d extra = integrals_in_frame(f, v.void_surfaces) - integrals_in_frame(f, cavity.written);
    solve.correct(cavity.summary.rounds->back().delta_in_frame + extra, 100 + attempt);
    cavity = make_offset_cavity(options, f, b, solve, timings, say, extra);
  }
  timings.openings = seconds_since(start);
  return summary;
}

// Where a volume held behind an opening starts its ball (ReachabilityOptions::volume_start): on
// the channel's axis for a half-space, on the line from the vertices' mean to a sphere region's
// centre, so that the opening cut to it is short (on the demo sphere through z>55, the channel
// held 1587 of a target of 1000 with the ball at the middle). None for any other goal or region.
std::optional<ReachabilityOptions::Line> volume_start_for(const Mesh& input, const OptimizeOptions& options, double wall) {
  if (options.goal != GoalKind::volume) return std::nullopt;
  if (options.fix.kind == FixRegion::Kind::half_space) {
    std::string why;
    const std::optional<ChannelAxis> axis = channel_axis(input, options.fix, wall, why);
    if (axis) return ReachabilityOptions::Line{axis->point, axis->direction};
  } else if (options.fix.kind == FixRegion::Kind::sphere) {
    const Eigen::Vector3d centre(options.fix.center[0], options.fix.center[1], options.fix.center[2]);
    const Eigen::Vector3d towards = centre - input.V.colwise().mean().transpose();
    if (towards.norm() > 0.0) return ReachabilityOptions::Line{centre, towards};
  }
  return std::nullopt;
}

// Stage "report": the frame, the field, the solver and the input as it was, as values.
FieldSummary field_summary(const OptimizeOptions& options, const Band& b, const ReducedProblem::Evaluation& e) {
  FieldSummary field;
  field.contraction_steps = b.contraction.steps;
  field.contraction_status = b.contraction.status;
  field.volume_ratio = b.contraction.volume_ratio;
  field.shortened = b.field.shortened_count;
  field.fallback = b.field.fallback_count;
  field.fixed = b.fixed_count;
  field.left_solid_vertices = b.left_solid_count_initial;
  field.left_solid_vertices_after_repairs = b.left_solid_count;
  if (options.outer) field.outer_limit = b.outer_summary;
  for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(b.band.fixed.size()); ++i) {
    if (b.band.fixed[static_cast<std::size_t>(i)] || b.left_solid[static_cast<std::size_t>(i)]) continue;
    const double span = options.ramp;
    if (e.inner_offset(i) >= b.band.upper(i) - span) ++field.clamped_at_skeleton;
    else if (e.inner_offset(i) <= std::min(b.band.lower(i) - e.outer_offset(i), b.band.upper(i)) + span) ++field.clamped_at_wall;
  }
  return field;
}

SolverSummary solver_summary(const Frame& f, const OffsetSolve& solve) {
  SolverSummary solver;
  const ReducedProblem::Evaluation& e = solve.eval;
  solver.status = solve.solved.status;
  solver.objective = e.objective;
  solver.outer_iterations = solve.solved.outer_iterations;
  solver.inner_iterations = solve.solved.inner_iterations;
  solver.evaluations = solve.total_evaluations;
  solver.repair_rounds = solve.repair_rounds;
  solver.repairs = solve.repairs;
  solver.max_violation = solve.solved.max_violation;
  solver.variables = solve.variables;
  auto add_rows = [&](const std::vector<std::string>& names, const Eigen::VectorXd& values, bool equality) {
    for (std::size_t r = 0; r < names.size(); ++r)
      solver.constraints.push_back({names[r], equality, values(static_cast<Eigen::Index>(r))});
  };
  add_rows(goal_equality_names(f.goal), e.goal.equality, true);
  add_rows(goal_inequality_names(f.goal), e.goal.inequality, false);
  return solver;
}

// Why the result failed, starting with what happened to the solve.
std::string failure_reason(const OptimizeOptions& options, const Band& b, const OffsetSolve& solve,
                           const Verification& verification) {
  std::string why = verification.failures.empty() ? "unknown" : verification.failures.front();
  const AlResult& solved = solve.solved;
  const bool constraints_unmet = !constraints_met(solved, options);
  if (options.bounds == BoundsMode::hard && b.left_solid_count_initial > 0)
    return std::string("the per-vertex bounds cannot be met") + (options.k == 0 ? ": " : " in the basis: ") +
           std::to_string(b.left_solid_count_initial) +
           " vertices lie in parts thinner than two walls, where no offset is both above the wall and below the "
           "skeleton (try --bounds clamp); " + why;
  if (solved.status == AlStatus::invalid_input || solved.status == AlStatus::numerical_issue)
    return std::string("the solver could not start (") + to_string(solved.status) +
           (solved.message.empty() ? "" : ": " + solved.message) + "); " + why;
  const char* later = options.cavity == CavityMode::offset ? "repair" : "correction";
  if (constraints_unmet && solve.last_round_met >= 0)
    return std::string("the constraints were met before ") + later + " round " +
           std::to_string(solve.last_round_met + 1) + ", but not once " +
           (options.cavity == CavityMode::offset ? "the bounds were tightened there to remove folds and thin walls"
                                                  : "the contoured cavity's moments were taken into account") +
           "; " + why;
  if (constraints_unmet && solved.status == AlStatus::max_evaluations)
    return "the solver used its " + std::to_string(options.solver.max_evaluations) +
           " evaluations before meeting the constraints (violation " + format_double(solved.max_violation) +
           ", normalised frame); " + why;
  if (constraints_unmet)
    return "no offset in this basis meets the constraints (k too small, or a goal no void can reach); " + why;
  return why;
}

// No void can reach the goal (a checked certificate): the input is written as it is, exit 3. The
// report's `before` still counts the input's own crossings, as every other report does.
OptimizeResult refuse_unreachable(const Mesh& input, const OptimizeOptions& options, const Frame& f, ReachabilitySummary reach,
                                  StageTimings timings, Clock::time_point total_start) {
  OptimizeResult result;
  result.status = OptimizeStatus::goal_not_met;
  result.message = reach.refusal;
  result.outer = input;
  result.printable = input;
  result.goal = f.setup;
  result.frame = {f.origin, f.scale, f.diag, f.wall, f.outer_max, f.margin, f.ground_tol};
  const SelfIntersectionReport own = input_self_intersections(input, options);
  result.before = {f.before, f.stability_before.com_margin, f.stability_before.stands, own.pairs, own.truncated};
  result.after.goal.goal = f.goal_input.kind;
  timings.total = seconds_since(total_start);
  result.timings = timings;
  result.reachability = std::move(reach);
  return result;
}

}  // namespace

OptimizeResult optimize_offsets(const Mesh& input, const OptimizeOptions& options, const Progress& progress) {
  auto say = [&](const std::string& line) {
    if (progress) progress(line);
  };
  if (const std::string problem = options.check(); !problem.empty())
    return failure(OptimizeStatus::bad_input, problem);
  const Eigen::Index n = input.V.rows();
  const int k = options.k;
  if (k >= n) return failure(OptimizeStatus::bad_input, "--k " + std::to_string(k) + " is not below the vertex count " + std::to_string(n));

  StageTimings timings;
  auto stage_start = Clock::now();
  const auto total_start = stage_start;
  Frame f;
  if (const std::string problem = make_frame(input, options, f); !problem.empty())
    return failure(OptimizeStatus::bad_input, problem);
  timings.frame = seconds_since(stage_start);
  // The basis needs the mesh alone, so it is computed alongside the reachability programme and the
  // skeleton. All give the same bits on any number of threads, so running them together changes
  // no result. The future's destructor waits for the basis on every return below.
  struct BasisOutcome {
    LanczosResult harmonics;
    double seconds = 0.0;
  };
  std::future<BasisOutcome> basis_future;
  // Coarse to fine (skeleton/coarse_copy.h): above the contraction's coarse_above vertices the
  // skeleton and the basis, both low-frequency, are computed on one decimated copy and carried
  // back (at 10^6 vertices the basis cost 37 CPU s and the contraction would need 2 GB). With two
  // or more threads the copy is made alongside the reachability programme; the basis and the
  // skeleton wait for it.
  const ContractionOptions contraction_defaults;
  struct CoarseOutcome {
    std::optional<CoarseCopy> copy;
    Mesh mesh;  // the copy in the normalised frame
    double seconds = 0.0;
  };
  const bool use_coarse = contraction_defaults.coarse_above > 0 && n > contraction_defaults.coarse_above;
  if (use_coarse)
    say("coarse copy: " + std::to_string(contraction_defaults.coarse_vertices) + " of " + std::to_string(n) + " vertices");
  const auto make_coarse = [&input, &f, &options, use_coarse, target = contraction_defaults.coarse_vertices]() {
    CoarseOutcome outcome;
    if (!use_coarse) return outcome;
    const auto start = Clock::now();
    outcome.copy = coarse_copy(input.V, input.F, target, options.threads);
    const DecimatedMesh& d = outcome.copy->decimated;
    outcome.mesh.F = d.mesh.F;
    outcome.mesh.V.resize(d.mesh.V.rows(), 3);
    for (std::size_t c = 0; c < d.input_vertex.size(); ++c)
      outcome.mesh.V.row(static_cast<Eigen::Index>(c)) = f.normalized.V.row(d.input_vertex[c]);
    outcome.seconds = seconds_since(start);
    return outcome;
  };
  const std::shared_future<CoarseOutcome> coarse_future = start_task(options.threads > 1 && use_coarse, make_coarse).share();
  if (k > 0) {
    const bool alongside = options.threads > 1;
    say("basis: " + std::to_string(k) + " manifold harmonics" + (alongside ? ", alongside the skeleton" : ""));
    ManifoldHarmonicsOptions basis_options;
    basis_options.kind = options.basis;
    basis_options.lanczos.threads = options.threads;
    const auto& tick = options.on_stage_progress;
    if (tick) basis_options.lanczos.on_progress = [&tick](double fraction) { tick("basis", fraction); };
    const auto compute_basis = [&normalized = f.normalized, coarse_future, k, basis_options, &tick]() {
      const CoarseOutcome& coarse = coarse_future.get();  // its own seconds are the copy's
      const auto start = Clock::now();
      BasisOutcome outcome;
      if (tick) tick("basis", 0.0);
      outcome.harmonics = manifold_harmonics(coarse.copy ? coarse.mesh : normalized, k, basis_options);
      if (tick) tick("basis", 1.0);
      outcome.seconds = seconds_since(start);
      return outcome;
    };
    basis_future = start_task(alongside, compute_basis);
  }

  // The skeleton and the offset field need the input alone too: with two or more threads they are
  // computed alongside the reachability programme (on the 10^6-vertex bottle the programme and the
  // field with the input's self-intersection search each cost about 10 CPU s, one after the other
  // before). The outcome is the same bits either way; a goal no void reaches still stops first.
  const auto& tick = options.on_stage_progress;
  struct BandOutcome {
    Band band;
    std::string problem;
    double seconds = 0.0;
  };
  // The input's tree, once: the skeleton's field, the reachability programme and the quadric void
  // read it (10^6 vertices: about 0.6 s a tree).
  const auto input_bvh = std::make_shared<const TriangleBvh>(input.V, input.F);
  const auto compute_band = [&input, &input_bvh, &options, &f, coarse_future, &tick]() {
    const std::optional<CoarseCopy>& coarse = coarse_future.get().copy;
    const auto start = Clock::now();
    BandOutcome outcome;
    if (tick) tick("skeleton", 0.0);
    outcome.problem = make_band(input, input_bvh, options, f, coarse ? &*coarse : nullptr, outcome.band);
    outcome.seconds = seconds_since(start);
    if (tick) tick("skeleton", 1.0);
    return outcome;
  };
  say("skeleton: contracting " + std::to_string(n) + " vertices" + (options.threads > 1 ? ", alongside the reachability" : ""));
  std::future<BandOutcome> band_future = start_task(options.threads > 1, compute_band);

  // Reachability. With one thread it comes first, so that a goal no void reaches costs nothing
  // else. With two or more it has a task of its own, beside the skeleton and the basis and then
  // the solve: on `stand-filled --outer` the programme outlasts the other two by about 0.2 s, an
  // idle core the solve now fills. The solve does not read the programme, so its bits are the
  // same either way; when the goal is out of reach the solve is stopped (AlOptions::stop) and the
  // goal refused as before, with the same precedence over the skeleton's and the basis' errors.
  say("reachability: can any void reach the goal?");
  const ReachabilityStageInput reach_input{&input, f.goal_input, f.zmin, f.origin, f.wall, f.outer_max, f.ground_tol,
                                           options.outer, options.cavity_cells_per_wall, options.cavity_margin_cells,
                                           options.threads, options.flatten, input_bvh.get(), options.up,
                                           options.posed_stable, volume_start_for(input, options, f.wall)};
  std::atomic<bool> out_of_reach{false};
  std::atomic<bool> reach_running{options.threads > 1};
  struct ReachOutcome {
    ReachabilitySummary summary;
    double seconds = 0.0;
    QuadricAhead quadric_ahead;
  };
  const auto compute_reach = [&reach_input, &options, &f, &input, input_bvh, &out_of_reach, &reach_running, &tick, n]() {
    ReachOutcome outcome;
    if (tick) tick("reachability", -1.0);
    const auto start = Clock::now();
    outcome.summary = reachability_stage(reach_input);
    outcome.seconds = seconds_since(start);
    reach_running = false;
    if (tick) tick("reachability", 1.0);
    const ReachabilitySummary& reach = outcome.summary;
    if (reach.decided && !reach.reachable) {
      out_of_reach = true;
      return outcome;
    }
    // The quadric void reads the input, the frame and the programme alone: where quadric_ahead
    // says so it is started now, beside the skeleton, the basis and the solve, where the offset
    // void's stages would otherwise run before it (make_cavity takes it if it wants it). The
    // result is the same on any number of threads.
    if (quadric_ahead(options, n) && quadric_possible(options, reach))
      outcome.quadric_ahead = start_task(true, [&input, &options, &f, input_bvh, programme = reach.programme, n]() {
        return attempt_quadric(options, f, input, *input_bvh, *programme, large_input(n) ? 1 : options.threads);
      });
    return outcome;
  };
  std::future<ReachOutcome> reach_future = start_task(options.threads > 1, compute_reach);
  std::optional<ReachOutcome> reached;
  // The programme's outcome, waited for once; true when the goal is out of reach.
  const auto refused = [&reach_future, &reached]() {
    if (!reached) reached = reach_future.get();
    return reached->summary.decided && !reached->summary.reachable;
  };
  const auto refuse = [&]() {
    timings.reach = reached->seconds;
    return refuse_unreachable(input, options, f, std::move(reached->summary), timings, total_start);
  };
  if (options.threads <= 1 && refused()) return refuse();

  BandOutcome band_outcome = band_future.get();
  const std::optional<CoarseCopy>& coarse = coarse_future.get().copy;
  const Mesh& basis_mesh = coarse_future.get().mesh;
  if (coarse) timings.coarse = coarse_future.get().seconds;
  if (!band_outcome.problem.empty()) {
    if (refused()) return refuse();
    return failure(OptimizeStatus::bad_input, band_outcome.problem);
  }
  Band b = std::move(band_outcome.band);
  timings.skeleton = band_outcome.seconds;

  // Basis: its own seconds, which overlap the skeleton's.
  Eigen::MatrixXd basis, coarse_basis;
  BasisSummary basis_summary;
  basis_summary.identity = k == 0;
  basis_summary.kind = options.basis;
  basis_summary.k = k == 0 ? static_cast<int>(n) : k;
  double basis_seconds = 0.0;
  if (k > 0) {
    BasisOutcome outcome = basis_future.get();
    basis_seconds = outcome.seconds;
    const LanczosResult& harmonics = outcome.harmonics;
    basis_summary.status = harmonics.status;
    basis_summary.largest_eigenvalue = harmonics.eigenvalues.size() ? harmonics.eigenvalues(harmonics.eigenvalues.size() - 1) : 0.0;
    if (harmonics.eigenvectors.cols() != k) {
      if (refused()) return refuse();
      return failure(OptimizeStatus::bad_input, "the eigensolver returned no basis: " + harmonics.message);
    }
    if (coarse) coarse_basis = harmonics.eigenvectors;
    basis = coarse ? carry_to_input(*coarse, harmonics.eigenvectors) : harmonics.eigenvectors;
  }
  timings.basis = basis_seconds;

  stage_start = Clock::now();
  ReducedOptions reduced_options;
  reduced_options.ramp_width = options.ramp;
  reduced_options.outer = options.outer;
  reduced_options.outer_penalty = options.penalty;
  reduced_options.bounds = options.bounds;
  reduced_options.start_fraction = options.start_fraction;
  reduced_options.threads = options.threads;
  reduced_options.serial_while = &reach_running;
  if (const std::string problem_text = reduced_options.check(); !problem_text.empty()) {
    if (refused()) return refuse();
    return failure(OptimizeStatus::bad_input, problem_text);
  }
  OptimizeOptions solve_options = options;
  solve_options.solver.stop = &out_of_reach;
  OffsetSolve solve(input, solve_options, f, b, basis, reduced_options, say);
  if ((options.cavity == CavityMode::automatic || options.cavity == CavityMode::contour) && options.max_correction_rounds >= 1)
    solve.hand_off_for_folds([&options, &f, &b](const Mesh& outer, const Mesh& inner, const ReducedProblem::Evaluation& at) {
      return predict_folds(options, f, b, outer, inner, at, offset_contour_options(options, f, outer), Vector10d::Zero());
    });
  if (tick) tick("solve", 0.0);
  // Only where an evaluation on the copy is much cheaper: on the 113k bottle the copy's 163
  // evaluations cost about the 34 they saved on the input (104 -> 70); at 10^6 they cost 1/33.
  if (coarse && coarse_basis.size() && n >= 8 * static_cast<Eigen::Index>(coarse->decimated.input_vertex.size())) {
    int coarse_evaluations = 0;
    if (std::optional<AlResult> first =
            coarse_solve(solve_options, f, b, *coarse, basis_mesh, coarse_basis, reduced_options, coarse_evaluations)) {
      say("solve on the coarse copy: " + std::to_string(coarse_evaluations) + " evaluations");
      solve.warm_start(std::move(*first));
    }
  }
  solve.run();
  timings.solve = seconds_since(stage_start);
  if (tick) tick("solve", 1.0);
  if (refused()) return refuse();
  timings.reach = reached->seconds;
  ReachabilitySummary reach = std::move(reached->summary);
  QuadricAhead& quadric_ahead = reached->quadric_ahead;

  Cavity cavity = make_cavity(options, f, b, solve, reach, timings, say, quadric_ahead.valid() ? &quadric_ahead : nullptr);
  std::optional<OpeningsSummary> openings;
  std::optional<Mesh> opened_solid;
  if ((options.wants_drain_holes() || wants_channel(options, b)) && cavity.summary.contoured())
    openings = cut_openings(options, f, b, solve, reach.programme.get(), cavity, opened_solid, timings, say);
  timings.total = seconds_since(total_start);

  OptimizeResult result;
  result.outer = cavity.outer;
  result.inner = cavity.written;
  result.printable = opened_solid                  ? *opened_solid
                     : cavity.summary.contoured() ? hollow_solid(cavity.outer, cavity.written)
                                                  : printable_solid(cavity.outer, cavity.written, b.band.fixed);
  result.openings = std::move(openings);
  result.skeleton = Mesh{b.contraction.V, input.F};
  result.goal = f.setup;
  result.frame = {f.origin, f.scale, f.diag, f.wall, f.outer_max, f.margin, f.ground_tol};
  result.field = field_summary(options, b, solve.eval);
  result.basis = basis_summary;
  result.solver = solver_summary(f, solve);
  result.before = {f.before, f.stability_before.com_margin, f.stability_before.stands, b.input_self.pairs,
                   b.input_self.truncated};
  result.cavity = cavity.summary;
  result.after = cavity.verification;
  // Not with --outer: the programme's band adds material but does not model the outer surface's
  // shaving, so its best is no bound on what the thickened solid reaches.
  if (reach.programme && !options.outer) result.optimality = optimality(f, *reach.programme, cavity.verification);
  result.timings = timings;
  result.reachability = std::move(reach);
  // The input's own crossings are named where it is loaded (meshio/load_input.h); the
  // report keeps their count, and the verification counts only the cavity's.
  // "Parts thinner than two walls" is the users' wording for parts left solid (kept as it was).
  if (b.left_solid_count > 0)
    result.warnings.push_back(std::to_string(b.left_solid_count) + " vertices lie in parts thinner than two walls" +
                              (cavity.summary.contoured() ? "; those parts stay solid" : ", where the offset surface leaves less than the wall"));
  if (b.field.fallback_count > 0)
    result.warnings.push_back(std::to_string(b.field.fallback_count) + " vertices move along the inward normal (skeleton direction unusable or too shallow)");
  // Below the centre of so large a sphere is where any solid's centre of mass already is: the goal
  // is met, and says nothing about rocking.
  if (options.goal == GoalKind::roly_poly && !(options.radius > 0.0) &&
      f.setup.sphere_radius > kFlatBottomDiagonals * f.diag)
    result.warnings.push_back("the sphere fitted to the bottom has radius " + format_double(f.setup.sphere_radius) + ", " +
                              format_double(std::round(f.setup.sphere_radius / f.diag)) +
                              " times the model's diagonal: the bottom is nearly flat, so the object stands rather than "
                              "rocks; give --radius for the sphere it should rock on");
  const Verification& verification = cavity.verification;
  if (verified(verification)) {
    result.status = OptimizeStatus::verified;
    if (result.reachability) credit_written_solid(*result.reachability, f.goal.kind, verification);
    // The solver's tolerance (1e-8 of the diagonal) is far tighter than the goals' (1e-4 for the
    // axis goals), so a small basis can end above the first and still pass: say so, as the
    // report's solver status alone would read as a failure.
    const AlResult& solved = solve.solved;
    const bool offset_written = cavity.summary.written != WrittenCavity::quadric;
    if (offset_written && !constraints_met(solved, options))
      result.warnings.push_back(std::string("the solver ended ") + to_string(solved.status) + " with constraint violation " +
                                format_double(solved.max_violation) + " (tolerance " +
                                format_double(options.solver.feasibility_tolerance) +
                                ", normalised frame); the written object still meets every tolerance the verification checks");
  } else {
    result.status = OptimizeStatus::goal_not_met;
    const CavitySummary& written = cavity.summary;
    if (written.written == WrittenCavity::quadric) {
      result.message = "the quadric void: " + (verification.failures.empty() ? std::string("unknown") : verification.failures.front());
    } else {
      result.message = failure_reason(options, b, solve, verification);
      if (written.quadric_rounds) result.message += "; the quadric void was tried: " + written.choice;
    }
    if (result.reachability && (result.reachability->reachable || !result.reachability->decided)) {
      ReachabilityStageInput missed = reach_input;
      missed.bound_undecided = true;
      bound_undecided(missed, *result.reachability);
      confirm_reachable(missed, *result.reachability);
      add_remedies(missed, *result.reachability);
      result.message += "; " + reachability_note(*result.reachability);
    }
  }
  return result;
}

}  // namespace offsetopt
