// See optimize_report.h. Every key and its place in the object is the report's contract (the
// golden files in tests/golden compare it byte for byte): add keys at the end of an object.
#include "cli/optimize_report.h"

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cli/cli_support.h"
#include "mass/mass_properties.h"

namespace offsetopt::cli {

namespace {

Json strings(const std::vector<std::string>& lines) {
  Json out = Json::array();
  for (const auto& line : lines) out.push_back(line);
  return out;
}

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

Json stability_json(const StabilityFigures& s) {
  Json j = Json::object();
  j["com_margin"] = s.com_margin;
  j["tipping_angle_deg"] = s.tipping_angle_deg;
  j["stands"] = s.stands;
  return j;
}

Json parameters_json(const OptimizeOptions& options, const FrameSummary& frame) {
  Json params = Json::object();
  params["goal"] = to_string(options.goal);
  params["k"] = options.k == 0 ? Json("all") : Json(options.k);
  params["basis"] = to_string(options.basis);
  params["bounds"] = options.bounds == BoundsMode::clamp ? "clamp" : "hard";
  params["outer"] = options.outer;
  params["wall"] = frame.wall;
  params["outer_max"] = frame.outer_max;
  params["penalty"] = options.penalty;
  params["margin"] = frame.margin;
  params["ground_tol"] = frame.ground_tol;
  params["fill_density"] = options.fill_density;
  params["fluid_density"] = options.goal == GoalKind::floating ? Json(options.fluid_density) : Json();
  params["target_volume"] = options.goal == GoalKind::volume ? Json(options.target_volume) : Json();
  params["radius"] = options.radius > 0 ? Json(options.radius) : Json();
  params["fix"] = options.fix.kind == FixRegion::Kind::none ? Json() : Json(options.fix.text);
  params["gap"] = options.gap;
  params["ramp"] = options.ramp;
  params["start_fraction"] = options.start_fraction;
  params["repair_ring"] = options.repair_ring;
  params["cavity"] = to_string(options.cavity);
  return params;
}

Json goal_json(const GoalSetup& goal) {
  Json j = Json::object();
  j["name"] = to_string(goal.kind);
  if (goal.sphere_center) {
    j["sphere_center"] = vec3(*goal.sphere_center);
    j["sphere_radius"] = goal.sphere_radius;
  }
  if (goal.tip) j["tip"] = vec3(*goal.tip);
  return j;
}

Json frame_json(const FrameSummary& frame) {
  Json j = Json::object();
  j["origin"] = vec3(frame.origin);
  j["scale"] = frame.scale;
  j["diagonal"] = frame.diagonal;
  return j;
}

Json field_json(const FieldSummary& field) {
  Json j = Json::object();
  j["contraction_steps"] = field.contraction_steps;
  j["contraction_status"] = to_string(field.contraction_status);
  j["volume_ratio"] = field.volume_ratio;
  j["shortened"] = field.shortened;
  j["fallback"] = field.fallback;
  j["fixed"] = field.fixed;
  // The report's name for vertices in parts left solid.
  j["parts_left_solid"] = field.left_solid_vertices;
  j["parts_left_solid_after_repairs"] = field.left_solid_vertices_after_repairs;
  j["clamped_at_wall"] = field.clamped_at_wall;
  j["clamped_at_skeleton"] = field.clamped_at_skeleton;
  if (const auto& limit = field.outer_limit) {
    Json o = Json::object();
    o["free_limited"] = limit->free_limited;
    o["focal_limited"] = limit->focal_limited;
    o["nearest_limited"] = limit->nearest_limited;
    o["mean_fraction"] = limit->mean_fraction;
    o["fold_repairs"] = limit->fold_repairs;
    j["outer_limit"] = o;
  }
  return j;
}

Json basis_json(const BasisSummary& basis) {
  Json j = Json::object();
  j["kind"] = basis.identity ? "identity" : to_string(basis.kind);
  j["k"] = basis.k;
  if (basis.status) {
    j["status"] = to_string(*basis.status);
    j["largest_eigenvalue"] = basis.largest_eigenvalue;
  }
  return j;
}

Json solver_json(const SolverSummary& solver) {
  Json j = Json::object();
  j["status"] = to_string(solver.status);
  j["objective"] = solver.objective;
  j["outer_iterations"] = solver.outer_iterations;
  j["inner_iterations"] = solver.inner_iterations;
  j["evaluations"] = solver.evaluations;
  j["repair_rounds"] = solver.repair_rounds;
  Json repairs = Json::array();
  for (const RepairRound& repair : solver.repairs) {
    Json entry = Json::object();
    // "thin_wall" here is the verification's own term: walls below half the requested one.
    entry["intersecting_vertices"] = repair.intersecting_vertices;
    entry["thin_wall_vertices"] = repair.thin_wall_vertices;
    repairs.push_back(entry);
  }
  j["repairs"] = repairs;
  j["max_violation"] = solver.max_violation;
  j["variables"] = solver.variables;
  Json constraints = Json::array();
  for (const ConstraintValue& row : solver.constraints) {
    Json c = Json::object();
    c["name"] = row.name;
    c["type"] = row.equality ? "= 0" : "<= 0";
    c["value"] = row.value;
    constraints.push_back(c);
  }
  j["constraints_in_frame"] = constraints;
  return j;
}

Json before_json(const InputSummary& before) {
  Json j = properties_json(before.properties);
  Json stability = Json::object();
  stability["com_margin"] = before.com_margin;
  stability["stands"] = before.stands;
  j["stability"] = stability;
  // The input's own defects: the written solid keeps its outer surface, so they are the input's,
  // not the cavity's (the cavity's own intersections are counted in "after").
  j["self_intersecting_pairs"] = before.self_intersecting_pairs;
  j["self_intersections_truncated"] = before.self_intersections_truncated;
  return j;
}

Json contour_round_json(const ContourRound& round) {
  Json entry = Json::object();
  Json delta = Json::array();
  for (int r = 0; r < 10; ++r) delta.push_back(round.delta_in_frame(r));
  entry["delta_in_frame"] = delta;
  entry["void_volume_offset"] = round.void_volume_offset;
  entry["void_volume_contour"] = round.void_volume_contour;
  // Node counts written as numbers, as they always were.
  entry["grid"] = Json::array_of({static_cast<double>(round.grid.x()), static_cast<double>(round.grid.y()),
                                  static_cast<double>(round.grid.z())});
  entry["spacing"] = round.spacing;
  entry["contoured_cells"] = round.contoured_cells;
  entry["distance_nodes"] = round.distance_nodes;
  entry["shells"] = round.shells;
  entry["shells_filled"] = round.shells_filled;
  entry["filled_volume"] = round.filled_volume;
  entry["vertices_moved_for_wall"] = round.vertices_moved_for_wall;
  entry["vertices"] = round.vertices;
  entry["faces"] = round.faces;
  entry["goal_met"] = round.goal_met;
  entry["valid"] = round.valid ? Json(*round.valid) : Json();
  return entry;
}

Json cavity_json(const CavitySummary& cavity) {
  Json j = Json::object();
  j["mode"] = to_string(cavity.mode);
  j["offset_goal_met"] = cavity.offset_goal_met;
  j["offset_valid"] = cavity.offset_valid ? Json(*cavity.offset_valid) : Json();
  j["offset_failures"] = strings(cavity.offset_failures);
  if (cavity.fold_correction) {
    Json folds = Json::object();
    folds["void_volume"] = cavity.fold_correction->void_volume;
    folds["wall_cut_volume"] = cavity.fold_correction->wall_cut_volume;
    folds["predicted_violation"] = cavity.fold_correction->predicted_violation;
    j["fold_correction"] = folds;
  }
  if (cavity.rounds) {
    Json rounds = Json::array();
    for (const ContourRound& round : *cavity.rounds) rounds.push_back(contour_round_json(round));
    j["rounds"] = rounds;
  }
  if (cavity.quadric_rounds) {
    Json rounds = Json::array();
    for (const ContourRound& round : *cavity.quadric_rounds) rounds.push_back(contour_round_json(round));
    j["quadric_rounds"] = rounds;
  }
  if (cavity.offset_objective || cavity.quadric_objective) {
    j["offset_objective"] = cavity.offset_objective ? Json(*cavity.offset_objective) : Json();
    j["quadric_objective"] = cavity.quadric_objective ? Json(*cavity.quadric_objective) : Json();
  }
  j["written"] = to_string(cavity.written);
  if (!cavity.choice.empty()) j["choice"] = cavity.choice;
  return j;
}

void add_goal_figures(const GoalFigures& g, Json& m) {
  switch (g.goal) {
    case GoalKind::stand:
    case GoalKind::stand_filled:
      m["empty"] = stability_json(g.empty);
      if (g.goal == GoalKind::stand_filled) {
        m["filled"] = stability_json(g.filled);
        m["filled"]["center_of_mass"] = vec3(g.filled_center_of_mass);
      }
      break;
    case GoalKind::roly_poly:
      m["sphere_center"] = vec3(g.axis_point);
      m["com_off_axis"] = g.com_off_axis;
      m["com_below_center"] = g.com_below_center;
      break;
    case GoalKind::spin:
      m["tip"] = vec3(g.axis_point);
      m["com_off_axis"] = g.com_off_axis;
      m["Izx_over_Izz"] = g.izx_over_izz;
      m["Iyz_over_Izz"] = g.iyz_over_izz;
      m["principal_moments"] = vec3(g.principal_moments);
      m["spin_axis_tilt_deg"] = g.spin_axis_tilt_deg;
      m["spin_axis_is_largest_moment"] = g.spin_axis_is_largest_moment;
      break;
    case GoalKind::volume:
      m["target_volume"] = g.target_volume;
      m["volume_relative_error"] = g.volume_relative_error;
      break;
    case GoalKind::floating:
      m["center_of_buoyancy"] = vec3(g.center_of_buoyancy);
      m["buoyancy_minus_weight"] = g.buoyancy_minus_weight;
      m["com_off_buoyancy_axis"] = g.com_off_buoyancy_axis;
      m["com_below_buoyancy"] = g.com_below_buoyancy;
      break;
  }
}

}  // namespace

Json verification_json(const Verification& verification) {
  const GoalFigures& g = verification.goal;
  Json m = Json::object();
  m["mass"] = g.mass;
  m["void_volume"] = g.void_volume;
  m["outer_volume"] = g.outer_volume;
  m["center_of_mass"] = vec3(g.center_of_mass);
  add_goal_figures(g, m);
  if (const auto& v = verification.validity) {
    m["inner_self_intersections"] = v->inner_self_intersections;
    m["inner_outer_crossings"] = v->inner_outer_crossings;
    m["cavity_unmatched_edges"] = v->cavity_unmatched_edges;
    if (v->outer_new_self_intersections) {
      m["outer_new_self_intersections"] = *v->outer_new_self_intersections;
      m["outer_own_self_intersections"] = v->outer_own_self_intersections.value_or(0);
    }
    m["requested_wall"] = v->requested_wall;
    m["min_wall_measured"] = v->min_wall_measured ? Json(*v->min_wall_measured) : Json();
    m["min_wall_vertex"] = v->min_wall_vertex;
    m["largest_bound_violation"] = v->largest_bound_violation;
    if (v->precision == StoredPrecision::float32) {
      // Verified as an STL reads back (absent for .ply, .obj, .3mf outputs, which keep every digit).
      Json rounding = Json::object();
      rounding["precision"] = "float32";
      rounding["vertices_moved"] = v->vertices_moved_for_rounding;
      rounding["new_defects"] = v->rounding_new_defects;
      m["rounded_for_output"] = rounding;
    }
    m["goal_met"] = verification.goal_met;
    m["valid"] = verification.valid;
    m["failures"] = strings(verification.failures);
  } else {
    // Validity not measured: a contour that was to be corrected, when the next round could not be
    // contoured; "valid" (false) follows the failures there.
    m["goal_met"] = verification.goal_met;
    m["failures"] = strings(verification.failures);
    m["valid"] = verification.valid;
  }
  return m;
}

Json stage_timings_json(const StageTimings& timings) {
  // In stage order; contour and correct only when a contour was attempted.
  const std::pair<const char*, std::optional<double>> stages[] = {
      {"frame", timings.frame},     {"coarse", timings.coarse},     {"skeleton", timings.skeleton}, {"basis", timings.basis},
      {"solve", timings.solve},     {"verify", timings.verify},     {"contour", timings.contour},
      {"correct", timings.correct}, {"reach", timings.reach},     {"quadric", timings.quadric}, {"openings", timings.openings},
      {"total", timings.total}};
  Json j = Json::object();
  for (const auto& [key, seconds] : stages)
    if (seconds) j[key] = *seconds;
  return j;
}

Json optional_number(const std::optional<double>& value) { return value ? Json(*value) : Json(); }

// docs/reachability.md describes every key.
Json reachability_json(const ReachabilitySummary& r) {
  Json j = Json::object();
  j["reachable"] = r.reachable;
  j["decided"] = r.decided;
  j["evidence"] = r.evidence.empty() ? Json() : Json(r.evidence);
  j["best_margin"] = optional_number(r.best_margin);
  j["best_margin_upper"] = optional_number(r.best_margin_upper);
  j["binding"] = r.binding.empty() ? Json() : Json(r.binding);
  if (r.certificate) {
    Json c = Json::object();
    c["origin"] = Json::array_of({r.certificate_origin.x(), r.certificate_origin.y(), r.certificate_origin.z()});
    Json q = Json::array();
    for (int k = 0; k < 10; ++k) q.push_back(r.quadric(k));
    c["quadric"] = q;
    j["certificate"] = c;
  } else {
    j["certificate"] = Json();
  }
  j["lowest_cz"] = optional_number(r.lowest_cz);
  Json remedies = Json::array();
  for (const ReachabilityRemedy& remedy : r.remedies) {
    Json m = Json::object();
    m["option"] = remedy.option;
    m["reachable"] = remedy.reachable;
    m["decided"] = remedy.decided;
    m["mid_cells_reach"] = remedy.mid_cells_reach;
    m["best_margin"] = optional_number(remedy.best_margin);
    remedies.push_back(m);
  }
  j["remedies"] = remedies;
  j["carvable_volume"] = r.carvable_volume;
  j["cell_spacing"] = r.cell_spacing;
  j["linear_programmes"] = r.lps;
  j["simplex_iterations"] = r.lp_iterations;
  return j;
}

// The openings cut through the cavity (drain holes, the channel): where, how wide, the void and
// liquid they leave.
Json openings_json(const OpeningsSummary& o) {
  Json j = Json::object();
  Json list = Json::array();
  for (const CutOpening& c : o.openings) {
    Json e = Json::object();
    e["kind"] = c.kind;
    e["inner"] = vec3(c.inner);
    e["outer"] = vec3(c.outer);
    e["radius"] = c.radius;
    if (c.shell >= 0) e["cavity_shell"] = c.shell;
    e["tries"] = c.tries;
    list.push_back(e);
  }
  j["cut"] = list;
  j["cavity_shells"] = o.cavity_shells;
  j["void_volume"] = o.void_volume;
  if (o.spill_height) j["spill_height"] = *o.spill_height;
  if (o.liquid_volume) j["liquid_volume"] = *o.liquid_volume;
  j["closed"] = o.closed;
  j["new_face_pairs"] = o.new_pairs;
  j["chips_dropped"] = o.chips_dropped;
  j["rounds"] = o.rounds;
  if (!o.message.empty()) j["problem"] = o.message;
  return j;
}

Json optimize_report(const OptimizeOptions& options, const OptimizeResult& result) {
  Json report = Json::object();
  report["parameters"] = parameters_json(options, result.frame);
  report["goal"] = goal_json(result.goal);
  report["frame"] = frame_json(result.frame);
  report["offset_field"] = field_json(result.field);
  report["basis"] = basis_json(result.basis);
  report["solver"] = solver_json(result.solver);
  report["before"] = before_json(result.before);
  report["cavity"] = cavity_json(result.cavity);
  report["after"] = verification_json(result.after);
  if (result.openings) report["openings"] = openings_json(*result.openings);
  if (result.optimality) {
    Json o = Json::object();
    o["fraction"] = result.optimality->fraction;
    o["before"] = result.optimality->before;
    o["written"] = result.optimality->written;
    o["best"] = result.optimality->best;
    report["optimality"] = o;
  }
  report["goal_met"] = result.after.goal_met;
  report["valid"] = result.after.valid;
  if (result.status == OptimizeStatus::goal_not_met) report["why"] = result.message;
  if (result.reachability) report["reachability"] = reachability_json(*result.reachability);
  return report;
}

}  // namespace offsetopt::cli
