#include "shape/offset_optimization.h"

#include <chrono>
#include <cmath>
#include <future>
#include <limits>
#include <memory>
#include <set>
#include <system_error>

#include <Eigen/Cholesky>

#include "geometry/bvh.h"
#include "geometry/intersecting_faces.h"
#include "mass/mass_properties.h"
#include "mass/stability.h"
#include "mass/volume_integrals.h"
#include "shape/contour_cavity.h"
#include "shape/offset_field.h"
#include "shape/printable_solid.h"
#include "shape/verify_offsets.h"
#include "skeleton/laplacian_contraction.h"
#include "util/format_double.h"

namespace offsetopt {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

Json vec3(const Eigen::Vector3d& v) { return Json::array_of({v.x(), v.y(), v.z()}); }

Json properties_json(const Vector10d& P) {
  Json j = Json::object();
  j["mass"] = P(kMass);
  j["center_of_mass"] = Json::array_of({P(kCx), P(kCy), P(kCz)});
  Json inertia = Json::object();
  inertia["xx"] = P(kIxx);
  inertia["yy"] = P(kIyy);
  inertia["zz"] = P(kIzz);
  inertia["xy"] = P(kIxy);
  inertia["yz"] = P(kIyz);
  inertia["zx"] = P(kIzx);
  j["inertia"] = inertia;
  return j;
}

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

// The largest field below `values` with slope at most `slope` along mesh edges:
// out_i = min_j (values_j + slope * edge-path length from j to i) (Dijkstra; ties by index, so
// deterministic). Keeps the bounds from jumping between neighbours, where a jump folds the inner
// surface.
Eigen::VectorXd lipschitz_envelope(const Mesh& mesh, const Eigen::VectorXd& values, double slope) {
  const Eigen::Index n = mesh.V.rows();
  std::vector<std::vector<std::pair<int, double>>> neighbours(static_cast<std::size_t>(n));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int a = mesh.F(f, c), b = mesh.F(f, (c + 1) % 3);
      const double length = (mesh.V.row(a) - mesh.V.row(b)).norm() * slope;
      neighbours[static_cast<std::size_t>(a)].emplace_back(b, length);
      neighbours[static_cast<std::size_t>(b)].emplace_back(a, length);
    }
  Eigen::VectorXd out = values;
  std::set<std::pair<double, int>> queue;
  for (Eigen::Index i = 0; i < n; ++i) queue.emplace(out(i), static_cast<int>(i));
  while (!queue.empty()) {
    const auto [value, i] = *queue.begin();
    queue.erase(queue.begin());
    for (const auto& [j, length] : neighbours[static_cast<std::size_t>(i)]) {
      if (value + length < out(j)) {
        queue.erase({out(j), j});
        out(j) = value + length;
        queue.emplace(out(j), j);
      }
    }
  }
  return out;
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
  }
  return "auto";
}

bool parse_cavity_mode(const std::string& text, CavityMode& mode) {
  for (CavityMode m : {CavityMode::automatic, CavityMode::offset, CavityMode::contour})
    if (text == to_string(m)) {
      mode = m;
      return true;
    }
  return false;
}

std::string check_optimize_settings(const OptimizeSettings& s) {
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
  if (s.max_correction_rounds < 0 || s.max_correction_rounds > 20) return "correction rounds must be in [0, 20]";
  ContourCavityOptions cavity;
  cavity.wall = 1.0;
  cavity.cells_per_wall = s.cavity_cells_per_wall;
  cavity.margin_cells = s.cavity_margin_cells;
  if (const std::string problem = check_contour_cavity_options(cavity); !problem.empty()) return "cavity: " + problem;
  return check_al_params(s.solver);
}

OptimizeResult optimize_offsets(const Mesh& input, const OptimizeSettings& settings,
                                const std::function<void(const std::string&)>& progress) {
  auto say = [&](const std::string& line) {
    if (progress) progress(line);
  };
  if (const std::string problem = check_optimize_settings(settings); !problem.empty())
    return failure(OptimizeStatus::bad_input, problem);
  const Eigen::Index n = input.V.rows();
  const int k = settings.k;
  if (k >= n) return failure(OptimizeStatus::bad_input, "--k " + std::to_string(k) + " is not below the vertex count " + std::to_string(n));

  Json timings = Json::object();
  auto stage_start = Clock::now();
  const auto total_start = stage_start;

  // Frame: ground, support polygon, scale.
  const Eigen::Vector3d lo = input.V.colwise().minCoeff().transpose(), hi = input.V.colwise().maxCoeff().transpose();
  const double diag = (hi - lo).norm();
  const double scale = 1.0 / diag;
  auto length = [&](double value, double fraction) { return value >= 0.0 ? value : fraction * diag; };
  const double wall = length(settings.wall, 0.01), outer_max = length(settings.outer_max, 0.02);
  const double margin = length(settings.margin, 0.002), ground_tol = length(settings.ground_tol, 0.001);
  const Vector10d before = mass_properties(input);
  StabilityOptions stability_options;
  stability_options.ground_tol = ground_tol;
  const Stability stability_before =
      compute_stability(input, Eigen::Vector3d(before(kCx), before(kCy), before(kCz)), stability_options);
  const double zmin = stability_before.ground_z;
  Eigen::Vector2d contact_centroid = Eigen::Vector2d::Zero();
  int contacts = 0;
  for (Eigen::Index i = 0; i < n; ++i)
    if (input.V(i, 2) <= zmin + ground_tol) {
      contact_centroid += input.V.row(i).head<2>().transpose();
      ++contacts;
    }
  contact_centroid /= contacts;
  const Eigen::Vector3d frame_origin(contact_centroid.x(), contact_centroid.y(), zmin);
  auto to_frame = [&](const Eigen::Vector3d& p) { return Eigen::Vector3d((p - frame_origin) * scale); };
  Mesh normalized = input;
  for (Eigen::Index i = 0; i < n; ++i) normalized.V.row(i) = to_frame(input.V.row(i).transpose()).transpose();

  // The goal in input units (for verification) and in the frame (for the solver).
  GoalSpec goal_input;
  goal_input.kind = settings.goal;
  goal_input.margin = margin;
  goal_input.epsilon = margin;
  goal_input.fill_density = settings.fill_density;
  goal_input.fluid_density = settings.fluid_density;
  goal_input.target_volume = settings.target_volume;
  goal_input.support_polygon = stability_before.support_polygon;
  Json goal_json = Json::object();
  goal_json["name"] = to_string(settings.goal);
  if (settings.goal == GoalKind::roly_poly) {
    Eigen::Vector3d center;
    double radius = settings.radius;
    if (radius > 0.0) {
      Eigen::Index lowest = 0;
      input.V.col(2).minCoeff(&lowest);
      center = Eigen::Vector3d(input.V(lowest, 0), input.V(lowest, 1), zmin + radius);
    } else if (!fit_bottom_sphere(input, zmin, hi.z() - lo.z(), center, radius)) {
      return failure(OptimizeStatus::bad_input, "no sphere could be fitted to the bottom; give --radius");
    }
    goal_input.axis_point = center;
    goal_json["sphere_center"] = vec3(center);
    goal_json["sphere_radius"] = radius;
  } else if (settings.goal == GoalKind::spin) {
    Eigen::Index lowest = 0;
    input.V.col(2).minCoeff(&lowest);
    goal_input.axis_point = input.V.row(lowest).transpose();
    goal_json["tip"] = vec3(goal_input.axis_point);
  } else if (settings.goal == GoalKind::volume && settings.target_volume >= before(kMass)) {
    return failure(OptimizeStatus::bad_input, "--target-volume " + format_double(settings.target_volume) +
                                                  " is not below the object's volume " + format_double(before(kMass)));
  }
  if (const std::string problem = check_goal_spec(goal_input); !problem.empty())
    return failure(OptimizeStatus::bad_input, problem);
  GoalSpec goal = goal_input;
  for (auto& p : goal.support_polygon) p = (p - contact_centroid) * scale;
  // A hair of extra margin so the constraint met to the solver's tolerance is met exactly.
  goal.margin = margin * scale + 1e-7;
  goal.epsilon = margin * scale + 1e-7;
  goal.axis_point = to_frame(goal_input.axis_point);
  goal.target_volume = settings.target_volume * scale * scale * scale;
  timings["frame"] = seconds_since(stage_start);

  // The basis needs the mesh alone, so it is computed alongside the skeleton. Both give the same
  // bits on any number of threads, so running them together changes no result. The future's
  // destructor waits for the basis on every return below.
  struct BasisOutcome {
    LanczosResult harmonics;
    double seconds = 0.0;
  };
  std::future<BasisOutcome> basis_future;
  say("skeleton: contracting " + std::to_string(n) + " vertices");
  if (k > 0) {
    const bool alongside = settings.threads > 1;
    say("basis: " + std::to_string(k) + " manifold harmonics" + (alongside ? ", alongside the skeleton" : ""));
    ManifoldHarmonicsOptions basis_options;
    basis_options.kind = settings.basis;
    basis_options.lanczos.threads = settings.threads;
    const auto compute_basis = [&normalized, k, basis_options]() {
      const auto start = Clock::now();
      BasisOutcome outcome;
      outcome.harmonics = manifold_harmonics(normalized, k, basis_options);
      outcome.seconds = seconds_since(start);
      return outcome;
    };
    try {
      if (alongside) basis_future = std::async(std::launch::async, compute_basis);
    } catch (const std::system_error&) {
    }
    if (!basis_future.valid()) basis_future = std::async(std::launch::deferred, compute_basis);  // computed at get()
  }

  // Meso-skeleton and offset field (input units).
  stage_start = Clock::now();
  ContractionOptions contraction_options;
  contraction_options.threads = settings.threads;
  const ContractionResult contraction = laplacian_contraction(input.V, input.F, contraction_options);
  const TriangleBvh bvh(input.V, input.F);
  const IntersectingFaces input_self = self_intersections(bvh, 100000);
  OffsetFieldOptions field_options;
  field_options.wall = wall;
  field_options.threads = settings.threads;
  const OffsetField field = offset_field(input, contraction.V, bvh, field_options);
  timings["skeleton"] = seconds_since(stage_start);

  OffsetBand band;
  band.inner_direction = field.inner;
  band.outer_direction = field.outer;
  band.lower = field.lower * scale;
  band.upper = lipschitz_envelope(normalized, field.upper * ((1.0 - settings.gap) * scale), settings.bound_slope);
  band.fixed = fixed_vertices(input, settings.fix);
  int fixed_count = 0;
  for (char f : band.fixed) fixed_count += f ? 1 : 0;
  if (settings.fix.kind != FixRegion::Kind::none && fixed_count == 0)
    return failure(OptimizeStatus::bad_input, "--fix " + settings.fix.text + " selects no vertex");
  if (settings.outer) {
    // The base stays where it is: no outer offset within reach of the ground, so the object keeps
    // its contact set and its pose.
    band.outer_limit.resize(n);
    for (Eigen::Index i = 0; i < n; ++i)
      band.outer_limit(i) = input.V(i, 2) <= zmin + 2.0 * outer_max + ground_tol ? 0.0 : outer_max * scale;
  }
  std::vector<char> thin(static_cast<std::size_t>(n), 0);
  int thin_count = 0;
  auto mark_thin = [&]() {
    thin_count = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const bool collapsed = !band.fixed[static_cast<std::size_t>(i)] && band.lower(i) >= band.upper(i);
      thin[static_cast<std::size_t>(i)] = collapsed ? 1 : 0;
      thin_count += collapsed ? 1 : 0;
    }
  };
  mark_thin();
  const int thin_count_initial = thin_count;

  // Basis: its own seconds, which overlap the skeleton's.
  Eigen::MatrixXd basis;
  Json basis_json = Json::object();
  basis_json["kind"] = k == 0 ? "identity" : to_string(settings.basis);
  basis_json["k"] = k == 0 ? static_cast<int>(n) : k;
  double basis_seconds = 0.0;
  if (k > 0) {
    BasisOutcome outcome = basis_future.get();
    basis_seconds = outcome.seconds;
    const LanczosResult& harmonics = outcome.harmonics;
    basis_json["status"] = to_string(harmonics.status);
    basis_json["largest_eigenvalue"] = harmonics.eigenvalues.size() ? harmonics.eigenvalues(harmonics.eigenvalues.size() - 1) : 0.0;
    if (harmonics.eigenvectors.cols() != k)
      return failure(OptimizeStatus::bad_input, "the eigensolver returned no basis: " + harmonics.message);
    basis = harmonics.eigenvectors;
  }
  timings["basis"] = basis_seconds;

  // Solve. With `--cavity offset`, where the offset surfaces are not printable (the inner surface
  // folds onto itself or comes too close to the outside), tighten those vertices' bounds and solve
  // again from there; the other modes write a contoured cavity instead (below).
  stage_start = Clock::now();
  ReducedOptions reduced_options;
  reduced_options.ramp_width = settings.ramp;
  reduced_options.outer = settings.outer;
  reduced_options.outer_penalty = settings.penalty;
  reduced_options.bounds = settings.bounds;
  reduced_options.start_fraction = settings.start_fraction;
  reduced_options.threads = settings.threads;
  if (const std::string problem_text = check_reduced_options(reduced_options); !problem_text.empty())
    return failure(OptimizeStatus::bad_input, problem_text);
  OptimizeResult result;
  AlResult solved;
  ReducedProblem::Evaluation final_eval;
  Eigen::VectorXd x;
  int variables = 0, repair_rounds = 0, total_evaluations = 0;
  Json repairs = Json::array();
  int last_round_met = -1;  // the last round whose solve met the goal's constraints
  bool constraints_met = false;
  std::unique_ptr<ReducedProblem> problem;
  const int max_repair_rounds = settings.cavity == CavityMode::offset ? settings.max_repair_rounds : 0;
  auto warm_params = [&](int round) {
    AlParams solver_params = settings.solver;
    if (round > 0) {
      // A later round solves a nearby problem: start from the last round's multipliers and
      // penalty (measured on the bottle with --outer: 3605 evaluations without, 1124 with), the
      // penalty capped, because a huge one makes the first subproblem ill-conditioned (roly-poly:
      // 523 evaluations uncapped, 270 capped at 1e3).
      solver_params.initial_equality_multipliers = solved.equality_multipliers;
      solver_params.initial_inequality_multipliers = solved.inequality_multipliers;
      solver_params.initial_penalty = std::min(solved.penalty, settings.warm_penalty_cap);
    }
    if (settings.trace_solver)
      solver_params.on_outer_iteration = [&say, round](const AlIterationInfo& info) {
        say("  round " + std::to_string(round) + " outer " + std::to_string(info.outer_iteration) + ": f " +
            format_double(info.f) + ", violation " + format_double(info.max_violation) + ", stationarity " +
            format_double(info.stationarity) + ", penalty " + format_double(info.penalty) + ", inner " +
            to_string(info.inner_status) + " after " + std::to_string(info.inner_iterations) + " iterations, " +
            std::to_string(info.evaluations) + " evaluations");
      };
    return solver_params;
  };
  // Solves from x and sets the surfaces; false when the goal's constraints are not met.
  auto solve = [&](int round) {
    solved = augmented_lagrangian_minimize(problem->constrained_problem(), x, warm_params(round));
    total_evaluations += solved.evaluations;
    if (solved.x.size() == x.size()) x = solved.x;  // an invalid problem leaves x where it was
    final_eval = problem->evaluate(x);
    result.inner = input;
    result.outer = input;
    for (Eigen::Index i = 0; i < n; ++i) {
      result.inner.V.row(i) += (final_eval.inner_offset(i) / scale) * band.inner_direction.row(i);
      if (settings.outer) result.outer.V.row(i) += (final_eval.outer_offset(i) / scale) * band.outer_direction.row(i);
    }
    // A problem the solver refuses (hard bounds with an empty box) or cannot evaluate at the start
    // is not changed by tighter bounds or a correction either.
    const bool solver_refused = solved.status == AlStatus::InvalidInput || solved.status == AlStatus::NumericalIssue;
    constraints_met = !solver_refused && solved.status != AlStatus::Infeasible &&
                      solved.max_violation <= 100.0 * settings.solver.feasibility_tolerance;
    return constraints_met;
  };
  for (int round = 0;; ++round) {
    problem = std::make_unique<ReducedProblem>(normalized, band, basis, k == 0, goal, reduced_options);
    variables = problem->num_variables();
    if (round == 0) {
      x = problem->start_point();
      say("solve: " + std::to_string(variables) + " variables, goal " + to_string(settings.goal));
    }
    // Tightened bounds only shrink the feasible set: when the goal's constraints are not met,
    // repairs cannot help, and the report says why.
    if (solve(round)) last_round_met = round;
    if (round == max_repair_rounds || !constraints_met) break;
    const SurfaceDefects defects =
        find_surface_defects(result.outer, result.inner, band.fixed, thin, 0.5 * wall, settings.threads);
    if (defects.empty()) break;
    ++repair_rounds;
    Json entry = Json::object();
    entry["intersecting_vertices"] = static_cast<long long>(defects.intersecting_vertices.size());
    entry["thin_wall_vertices"] = static_cast<long long>(defects.thin_wall_vertices.size());
    repairs.push_back(entry);
    say("repair " + std::to_string(repair_rounds) + ": " + std::to_string(defects.intersecting_vertices.size()) +
        " vertices on folds, " + std::to_string(defects.thin_wall_vertices.size()) + " on thin walls");
    // A fold spans the faces around its vertices: their one-ring neighbours are tightened too,
    // or the fold moves next door and needs another round.
    std::vector<char> tighten(static_cast<std::size_t>(n), 0);
    for (int v : defects.intersecting_vertices) tighten[static_cast<std::size_t>(v)] = 1;
    if (settings.repair_ring)
      for (Eigen::Index f = 0; f < input.F.rows(); ++f) {
        bool touched = false;
        for (int c = 0; c < 3; ++c) touched = touched || tighten[static_cast<std::size_t>(input.F(f, c))] == 1;
        if (touched)
          for (int c = 0; c < 3; ++c) {
            char& mark = tighten[static_cast<std::size_t>(input.F(f, c))];
            if (mark == 0) mark = 2;
          }
      }
    for (Eigen::Index v = 0; v < n; ++v)
      if (tighten[static_cast<std::size_t>(v)]) band.upper(v) *= settings.repair_shrink;
    band.upper = lipschitz_envelope(normalized, band.upper, settings.bound_slope);
    for (int v : defects.thin_wall_vertices) band.lower(v) += 0.5 * wall * scale;
    mark_thin();
  }
  timings["solve"] = seconds_since(stage_start);

  // The offset surfaces as they are, verified on the user's numbers.
  stage_start = Clock::now();
  double bound_violation = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (band.fixed[static_cast<std::size_t>(i)]) continue;
    const double upper = band.upper(i) / scale;
    const double lower = std::min(band.lower(i) - final_eval.outer_offset(i), band.upper(i)) / scale;
    const double offset = final_eval.inner_offset(i) / scale;
    bound_violation = std::max({bound_violation, offset - upper, lower - offset});
  }
  result.skeleton = Mesh{contraction.V, input.F};
  VerifyInput verify_input;
  verify_input.outer = &result.outer;
  verify_input.inner = &result.inner;
  verify_input.goal = goal_input;
  verify_input.diagonal = diag;
  verify_input.ground_tol = ground_tol;
  verify_input.wall = wall;
  verify_input.fixed = band.fixed;
  verify_input.bound_violation = bound_violation;
  verify_input.threads = settings.threads;
  Verification verification = verify_offsets(verify_input);
  timings["verify"] = seconds_since(stage_start);
  Json cavity_json = Json::object();
  cavity_json["mode"] = to_string(settings.cavity);
  cavity_json["offset_goal_met"] = verification.goal_met;
  cavity_json["offset_valid"] = verification.valid;
  Json offset_failures = Json::array();
  for (const auto& f : verification.failures) offset_failures.push_back(f);
  cavity_json["offset_failures"] = offset_failures;
  const bool offset_verified = verification.goal_met && verification.valid;
  const bool want_contour = settings.cavity == CavityMode::contour ||
                            (settings.cavity == CavityMode::automatic && !offset_verified);
  std::string cavity_problem;
  if (want_contour && fixed_count > 0) {
    cavity_problem = "with an opening (--fix) only the offset surfaces can be written, and they do not verify";
  } else if (want_contour) {
    // The contoured cavity, corrected in moment space (DESIGN.md "The written cavity", step 4):
    // the goal is solved again on the offset model's integrals plus the difference the contour
    // made, warm-started, until the written solid verifies.
    stage_start = Clock::now();
    ContourCavityOptions cavity_options;
    cavity_options.wall = wall;
    cavity_options.cells_per_wall = settings.cavity_cells_per_wall;
    cavity_options.margin_cells = settings.cavity_margin_cells;
    cavity_options.threads = settings.threads;
    Json rounds = Json::array();
    double contour_seconds = 0.0;
    for (int round = 0;; ++round) {
      const auto contour_start = Clock::now();
      const TriangleBvh outer_offset_bvh = settings.outer ? TriangleBvh(result.outer.V, result.outer.F) : TriangleBvh();
      const ContourCavity contoured =
          contour_cavity(result.outer, settings.outer ? outer_offset_bvh : bvh, result.inner, cavity_options);
      contour_seconds += seconds_since(contour_start);
      if (!contoured.ok) {
        cavity_problem = "the cavity could not be contoured: " + contoured.message;
        break;
      }
      Mesh framed = contoured.cavity;
      for (Eigen::Index i = 0; i < framed.V.rows(); ++i) framed.V.row(i) = to_frame(framed.V.row(i).transpose()).transpose();
      const Vector10d delta = volume_integrals(framed, Eigen::Vector3d::Zero()).values - final_eval.inner_integrals;
      VerifyInput contour_input = verify_input;
      contour_input.inner = &contoured.cavity;
      contour_input.fixed.clear();
      contour_input.bound_violation = 0.0;  // the band bounds the offset model, not the contour
      verification = verify_offsets(contour_input);
      Json entry = Json::object();
      Json delta_json = Json::array();
      for (int r = 0; r < 10; ++r) delta_json.push_back(delta(r));
      entry["delta_in_frame"] = delta_json;
      entry["void_volume_offset"] = final_eval.inner_integrals(kIntVolume) / (scale * scale * scale);
      entry["void_volume_contour"] = (final_eval.inner_integrals(kIntVolume) + delta(kIntVolume)) / (scale * scale * scale);
      entry["grid"] = Json::array_of({static_cast<double>(contoured.grid.nx), static_cast<double>(contoured.grid.ny),
                                      static_cast<double>(contoured.grid.nz)});
      entry["spacing"] = contoured.grid.spacing;
      entry["contoured_cells"] = static_cast<long long>(contoured.active_cells);
      entry["distance_nodes"] = static_cast<long long>(contoured.distance_nodes);
      entry["shells"] = contoured.shells;
      entry["shells_filled"] = contoured.shells_dropped;
      entry["vertices_moved_for_wall"] = contoured.vertices_moved_for_wall;
      entry["vertices"] = static_cast<long long>(contoured.cavity.V.rows());
      entry["faces"] = static_cast<long long>(contoured.cavity.F.rows());
      entry["goal_met"] = verification.goal_met;
      entry["valid"] = verification.valid;
      rounds.push_back(entry);
      say("cavity round " + std::to_string(round) + ": " + std::to_string(contoured.active_cells) + " cells contoured, " +
          std::to_string(contoured.shells) + " shells, goal " + (verification.goal_met ? "met" : "not met") + ", " +
          (verification.valid ? "valid" : "not valid"));
      result.inner = contoured.cavity;
      // A correction cannot mend an invalid contour or a goal whose constraints the solver
      // could not meet.
      if ((verification.goal_met && verification.valid) || !verification.valid || !constraints_met ||
          round == settings.max_correction_rounds)
        break;
      problem->set_inner_integral_shift(delta);
      if (solve(round + 1)) last_round_met = round + 1;
    }
    cavity_json["rounds"] = rounds;
    timings["contour"] = contour_seconds;
    timings["correct"] = seconds_since(stage_start) - contour_seconds;
  }
  const bool contoured = want_contour && cavity_problem.empty();
  cavity_json["written"] = contoured ? "contour" : "offset";
  result.printable = contoured ? hollow_solid(result.outer, result.inner) : printable_solid(result.outer, result.inner, band.fixed);
  if (!cavity_problem.empty()) {
    verification.valid = false;
    verification.failures.insert(verification.failures.begin(), cavity_problem);
    Json failures = Json::array();
    for (const auto& f : verification.failures) failures.push_back(f);
    verification.metrics["failures"] = failures;
    verification.metrics["valid"] = false;
  }
  timings["total"] = seconds_since(total_start);

  // Report.
  Json report = Json::object();
  Json params = Json::object();
  params["goal"] = to_string(settings.goal);
  params["k"] = k == 0 ? Json("all") : Json(k);
  params["basis"] = to_string(settings.basis);
  params["bounds"] = settings.bounds == BoundsMode::clamp ? "clamp" : "hard";
  params["outer"] = settings.outer;
  params["wall"] = wall;
  params["outer_max"] = outer_max;
  params["penalty"] = settings.penalty;
  params["margin"] = margin;
  params["ground_tol"] = ground_tol;
  params["fill_density"] = settings.fill_density;
  params["fluid_density"] = settings.goal == GoalKind::floating ? Json(settings.fluid_density) : Json();
  params["target_volume"] = settings.goal == GoalKind::volume ? Json(settings.target_volume) : Json();
  params["radius"] = settings.radius > 0 ? Json(settings.radius) : Json();
  params["fix"] = settings.fix.kind == FixRegion::Kind::none ? Json() : Json(settings.fix.text);
  params["gap"] = settings.gap;
  params["ramp"] = settings.ramp;
  params["start_fraction"] = settings.start_fraction;
  params["repair_ring"] = settings.repair_ring;
  params["cavity"] = to_string(settings.cavity);
  report["parameters"] = params;
  report["goal"] = goal_json;
  Json frame = Json::object();
  frame["origin"] = vec3(frame_origin);
  frame["scale"] = scale;
  frame["diagonal"] = diag;
  report["frame"] = frame;

  Json field_json = Json::object();
  field_json["contraction_steps"] = contraction.steps;
  field_json["contraction_status"] = to_string(contraction.status);
  field_json["volume_ratio"] = contraction.volume_ratio;
  field_json["shortened"] = field.shortened_count;
  field_json["fallback"] = field.fallback_count;
  field_json["fixed"] = fixed_count;
  field_json["parts_left_solid"] = thin_count_initial;
  field_json["parts_left_solid_after_repairs"] = thin_count;
  int at_lower = 0, at_upper = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (band.fixed[static_cast<std::size_t>(i)] || thin[static_cast<std::size_t>(i)]) continue;
    const double span = settings.ramp;
    if (final_eval.inner_offset(i) >= band.upper(i) - span) ++at_upper;
    else if (final_eval.inner_offset(i) <= std::min(band.lower(i) - final_eval.outer_offset(i), band.upper(i)) + span) ++at_lower;
  }
  field_json["clamped_at_wall"] = at_lower;
  field_json["clamped_at_skeleton"] = at_upper;
  report["offset_field"] = field_json;
  report["basis"] = basis_json;

  Json solver = Json::object();
  solver["status"] = to_string(solved.status);
  solver["objective"] = final_eval.objective;
  solver["outer_iterations"] = solved.outer_iterations;
  solver["inner_iterations"] = solved.inner_iterations;
  solver["evaluations"] = total_evaluations;
  solver["repair_rounds"] = repair_rounds;
  solver["repairs"] = repairs;
  solver["max_violation"] = solved.max_violation;
  solver["variables"] = variables;
  Json constraints = Json::array();
  const auto eq_names = goal_equality_names(goal), ineq_names = goal_inequality_names(goal);
  auto add_rows = [&](const std::vector<std::string>& names, const Eigen::VectorXd& values, const char* type) {
    for (std::size_t r = 0; r < names.size(); ++r) {
      Json c = Json::object();
      c["name"] = names[r];
      c["type"] = type;
      c["value"] = values(static_cast<Eigen::Index>(r));
      constraints.push_back(c);
    }
  };
  add_rows(eq_names, final_eval.goal.equality, "= 0");
  add_rows(ineq_names, final_eval.goal.inequality, "<= 0");
  solver["constraints_in_frame"] = constraints;
  report["solver"] = solver;
  report["before"] = properties_json(before);
  report["before"]["stability"] = Json::object();
  report["before"]["stability"]["com_margin"] = stability_before.com_margin;
  report["before"]["stability"]["stands"] = stability_before.stands;
  // The input's own defects: the written solid keeps its outer surface, so they are the input's,
  // not the cavity's (the cavity's own intersections are counted in "after").
  report["before"]["self_intersecting_pairs"] = static_cast<long long>(input_self.pairs.size());
  report["before"]["self_intersections_truncated"] = input_self.truncated;
  report["cavity"] = cavity_json;
  report["after"] = verification.metrics;
  report["goal_met"] = verification.goal_met;
  report["valid"] = verification.valid;

  result.report = report;
  result.timings = timings;
  if (!input_self.pairs.empty())
    result.warnings.push_back("the input intersects itself (" + std::to_string(input_self.pairs.size()) +
                              (input_self.truncated ? "+" : "") + " face pairs, the first " +
                              std::to_string(input_self.pairs.front().first) + " and " +
                              std::to_string(input_self.pairs.front().second) +
                              "); the written solid keeps them, the cavity adds none");
  if (thin_count > 0)
    result.warnings.push_back(std::to_string(thin_count) + " vertices lie in parts thinner than two walls; those parts stay solid");
  if (field.fallback_count > 0)
    result.warnings.push_back(std::to_string(field.fallback_count) + " vertices move along the inward normal (skeleton direction unusable or too shallow)");
  if (verification.goal_met && verification.valid) {
    result.status = OptimizeStatus::verified;
    // The solver's tolerance (1e-8 of the diagonal) is far tighter than the goals' (1e-4 for the
    // axis goals), so a small basis can end above the first and still pass: say so, as the
    // report's solver status alone would read as a failure.
    if (solved.status == AlStatus::Infeasible || solved.max_violation > 100.0 * settings.solver.feasibility_tolerance)
      result.warnings.push_back(std::string("the solver ended ") + to_string(solved.status) + " with constraint violation " +
                                format_double(solved.max_violation) + " (tolerance " +
                                format_double(settings.solver.feasibility_tolerance) +
                                ", normalised frame); the written object still meets every tolerance the verification checks");
  } else {
    result.status = OptimizeStatus::goal_not_met;
    std::string why = verification.failures.empty() ? "unknown" : verification.failures.front();
    const bool constraints_unmet = solved.status == AlStatus::Infeasible ||
                                   solved.max_violation > 100.0 * settings.solver.feasibility_tolerance;
    if (settings.bounds == BoundsMode::hard && thin_count_initial > 0)
      why = std::string("the per-vertex bounds cannot be met") + (k == 0 ? ": " : " in the basis: ") +
            std::to_string(thin_count_initial) +
            " vertices lie in parts thinner than two walls, where no offset is both above the wall and below the "
            "skeleton (try --bounds clamp); " + why;
    else if (solved.status == AlStatus::InvalidInput || solved.status == AlStatus::NumericalIssue)
      why = std::string("the solver could not start (") + to_string(solved.status) +
            (solved.message.empty() ? "" : ": " + solved.message) + "); " + why;
    else if (constraints_unmet && last_round_met >= 0)
      why = "the constraints were met before repair round " + std::to_string(last_round_met + 1) +
            ", but not once the bounds were tightened there to remove folds and thin walls; " + why;
    else if (constraints_unmet && solved.status == AlStatus::MaxEvaluations)
      why = "the solver used its " + std::to_string(settings.solver.max_evaluations) +
            " evaluations before meeting the constraints (violation " + format_double(solved.max_violation) +
            ", normalised frame); " + why;
    else if (constraints_unmet)
      why = "no offset in this basis meets the constraints (k too small, or a goal no void can reach); " + why;
    result.message = why;
    result.report["why"] = why;
  }
  return result;
}

}  // namespace offsetopt
