// See write_preview.h.
#include "cli/write_preview.h"

#include <cmath>

#include "cli/cli_support.h"

namespace offsetopt::cli {

namespace {

bool read_vec3(const Json& j, Eigen::Vector3d& out) {
  if (j.type() != Json::Type::array || j.size() != 3) return false;
  for (std::size_t i = 0; i < 3; ++i) {
    const Json& e = j.at(i);
    if (e.type() != Json::Type::number && e.type() != Json::Type::integer) return false;
    out(static_cast<Eigen::Index>(i)) = e.as_number();
    if (!std::isfinite(out(static_cast<Eigen::Index>(i)))) return false;
  }
  return true;
}

bool is_number(const Json& j) { return j.type() == Json::Type::number || j.type() == Json::Type::integer; }

// A number field of `object`: absent or null leaves `out` alone; anything else but a finite
// number is an error.
bool optional_number(const Json& object, const char* key, double& out) {
  if (!object.contains(key) || object.at(key).is_null()) return true;
  if (!is_number(object.at(key))) return false;
  out = object.at(key).as_number();
  return std::isfinite(out);
}

}  // namespace

std::string preview_input_from_report(const Json& report, PreviewInput& input) {
  if (report.type() != Json::Type::object) return "the report is not a JSON object";
  if (!report.contains("parameters") || report.at("parameters").type() != Json::Type::object)
    return "the report has no 'parameters' object";
  const Json& parameters = report.at("parameters");
  if (!parameters.contains("goal") || parameters.at("goal").type() != Json::Type::string)
    return "the report has no 'parameters.goal' string";
  if (!parse_goal_kind(parameters.at("goal").as_string(), input.goal))
    return "unknown goal '" + parameters.at("goal").as_string() + "' in 'parameters.goal'";
  for (const auto& [key, target] : {std::pair<const char*, double*>{"margin", &input.margin},
                                    {"ground_tol", &input.ground_tol},
                                    {"fill_density", &input.fill_density},
                                    {"fluid_density", &input.fluid_density},
                                    {"target_volume", &input.target_volume}})
    if (!optional_number(parameters, key, *target)) return std::string("'parameters.") + key + "' is not a finite number";
  if (input.margin < 0.0) return "'parameters.margin' is negative";
  if (!(input.fill_density > 0.0)) return "'parameters.fill_density' must be positive";
  if (input.goal == GoalKind::floating && !(input.fluid_density > 0.0))
    return "goal float needs a positive 'parameters.fluid_density'";
  if (report.contains("before") && report.at("before").type() == Json::Type::object &&
      report.at("before").contains("center_of_mass")) {
    if (!read_vec3(report.at("before").at("center_of_mass"), input.before_com))
      return "'before.center_of_mass' is not three finite numbers";
    input.has_before_com = true;
  }
  if (report.contains("goal") && report.at("goal").type() == Json::Type::object) {
    const Json& goal = report.at("goal");
    if (goal.contains("sphere_center")) {
      if (!read_vec3(goal.at("sphere_center"), input.sphere_center)) return "'goal.sphere_center' is not three finite numbers";
      if (!goal.contains("sphere_radius") || !is_number(goal.at("sphere_radius")) ||
          !(goal.at("sphere_radius").as_number() > 0.0) || !std::isfinite(goal.at("sphere_radius").as_number()))
        return "'goal.sphere_radius' is not a positive number";
      input.sphere_radius = goal.at("sphere_radius").as_number();
      input.has_sphere = true;
    }
    if (goal.contains("tip")) {
      if (!read_vec3(goal.at("tip"), input.tip)) return "'goal.tip' is not three finite numbers";
      input.has_tip = true;
    }
  }
  if (report.contains("openings") && report.at("openings").type() == Json::Type::object &&
      report.at("openings").contains("cut") && report.at("openings").at("cut").type() == Json::Type::array) {
    const Json& cut = report.at("openings").at("cut");
    for (std::size_t i = 0; i < cut.size(); ++i) {
      const Json& e = cut.at(i);
      PreviewInput::Opening o;
      if (e.type() != Json::Type::object || !e.contains("inner") || !e.contains("outer") || !e.contains("radius") ||
          !read_vec3(e.at("inner"), o.inner) || !read_vec3(e.at("outer"), o.outer) || !is_number(e.at("radius")))
        return "'openings.cut' holds an entry without inner, outer and radius";
      o.radius = e.at("radius").as_number();
      input.openings.push_back(o);
    }
  }
  if (report.contains("after") && report.at("after").type() == Json::Type::object) {
    double v = -1.0;
    if (!optional_number(report.at("after"), "void_volume", v)) return "'after.void_volume' is not a finite number";
    input.void_volume = v;
  }
  return {};
}

void write_preview(const std::string& svg_path, const Mesh& solid, const Json& report, const std::string& report_name,
                   const std::vector<std::string>& inputs) {
  PreviewInput input;
  if (const std::string problem = preview_input_from_report(report, input); !problem.empty())
    throw UsageError(problem + ", " + report_name);
  const PreviewResult picture = preview_svg(solid, input);
  if (picture.status != PreviewStatus::ok) throw UsageError("cannot draw the preview: " + picture.message);
  write_text(svg_path, picture.svg, inputs);
}

}  // namespace offsetopt::cli
