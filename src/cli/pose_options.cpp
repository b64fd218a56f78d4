#include "cli/pose_options.h"

#include "geometry/flatten_base.h"
#include "mass/mass_properties.h"
#include "mass/stable_pose.h"
#include "meshio/validate_mesh.h"
#include "util/format_double.h"

namespace offsetopt::cli {

namespace {

Json matrix_rows(const Eigen::Matrix3d& R) {
  Json rows = Json::array();
  for (int i = 0; i < 3; ++i) rows.push_back(Json::array_of({R(i, 0), R(i, 1), R(i, 2)}));
  return rows;
}

}  // namespace

bool parse_pose_option(const std::string& arg, ArgCursor& cursor, PoseOptions& options) {
  if (arg == "--up") {
    const std::string& value = cursor.value_of(arg);
    AxisPermutation permutation;
    if (!up_axis_permutation(value, permutation)) throw UsageError("--up must be +x, -x, +y, -y, +z or -z, got '" + value + "'");
    options.up = value.size() == 1 ? "+" + value : value;
    return true;
  }
  if (arg == "--pose") {
    const std::string& value = cursor.value_of(arg);
    if (value == "stable") options.stable = true;
    else if (value == "as-is") options.stable = false;
    else throw UsageError("--pose must be as-is or stable, got '" + value + "'");
    return true;
  }
  if (arg == "--flatten") {
    options.flatten = parse_in_range(cursor.value_of(arg), arg, kPoseOptionSpecs[2].range);
    return true;
  }
  return false;
}

std::string PoseOptions::check() const {
  AxisPermutation permutation;
  if (!up_axis_permutation(up, permutation)) return "--up must be +x, -x, +y, -y, +z or -z, got '" + up + "'";
  if (!(flatten >= 0.0 && flatten <= 1e12)) return "--flatten must be in (0, 1e12]";
  return {};
}

PosedInput pose_input(const Mesh& mesh, const PoseOptions& options, const std::string& mesh_path, bool single_component) {
  if (const std::string problem = options.check(); !problem.empty()) throw UsageError(problem);
  PosedInput posed;
  up_axis_permutation(options.up, posed.up);
  posed.mesh = permute_axes(mesh, posed.up);
  Json& report = posed.report;
  report["up"] = options.up;
  report["up_rotation"] = matrix_rows(posed.up.matrix());
  Eigen::Matrix3d rotation = posed.up.matrix();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  report["stable"] = Json();
  if (options.stable) {
    const Vector10d P = mass_properties(posed.mesh);
    const StablePose pose = stable_pose(posed.mesh, P.segment<3>(kCx));
    if (pose.status == StablePoseStatus::no_hull || pose.status == StablePoseStatus::bad_options)
      throw UsageError(mesh_path + ": --pose stable: " + pose.message);
    if (pose.status != StablePoseStatus::ok) posed.warnings.push_back("--pose stable: " + pose.message);
    posed.mesh = apply_rigid_motion(posed.mesh, pose.motion);
    posed.outputs_in_input_frame = false;
    Json stable = Json::object();
    stable["rotation"] = matrix_rows(pose.motion.rotation);
    stable["translation"] = Json::array_of({pose.motion.translation.x(), pose.motion.translation.y(), pose.motion.translation.z()});
    stable["margin"] = pose.margin;
    stable["facet_area"] = pose.facet_area;
    stable["facet_vertices"] = pose.facet_vertices;
    stable["hull_facets"] = pose.facet_count;
    report["stable"] = stable;
    rotation = pose.motion.rotation * rotation;
    translation = pose.motion.translation;
  }
  report["flatten"] = Json();
  if (options.flatten > 0.0) {
    const FlattenResult cut = flatten_base(posed.mesh, FlattenOptions{options.flatten});
    if (cut.status != FlattenStatus::ok) throw UsageError(mesh_path + ": --flatten " + format_double(options.flatten) + ": " + cut.message);
    const MeshValidation validation = validate_mesh(cut.mesh);
    for (const Defect& defect : validation.defects) {
      if (defect.kind == DefectKind::several_components && !single_component) continue;
      // The cut mesh's numbers mean nothing to the user: say where, in the working frame.
      std::string where;
      const long long v = defect.vertex >= 0 ? defect.vertex : defect.face >= 0 ? cut.mesh.F(defect.face, 0) : -1;
      if (v >= 0 && v < cut.mesh.V.rows())
        where = ", near (" + format_double(cut.mesh.V(v, 0)) + ", " + format_double(cut.mesh.V(v, 1)) + ", " +
                format_double(cut.mesh.V(v, 2)) + ") in the turned frame";
      throw UsageError(mesh_path + ": --flatten " + format_double(options.flatten) + " leaves no valid solid: " +
                       defect_name(defect.kind) + where + " (try another height)");
    }
    Json flatten = Json::object();
    flatten["height"] = options.flatten;
    flatten["plane_z"] = cut.plane_z;
    flatten["removed_vertices"] = cut.removed_vertices;
    flatten["snapped_vertices"] = cut.snapped_vertices;
    flatten["cut_edges"] = cut.cut_edges;
    flatten["cap_loops"] = cut.cap_loops;
    flatten["cap_holes"] = cut.cap_holes;
    flatten["cap_faces"] = cut.cap_faces;
    flatten["vertices"] = static_cast<long long>(cut.mesh.V.rows());
    flatten["faces"] = static_cast<long long>(cut.mesh.F.rows());
    report["flatten"] = flatten;
    posed.mesh = cut.mesh;
  }
  report["rotation"] = matrix_rows(rotation);
  report["translation"] = Json::array_of({translation.x(), translation.y(), translation.z()});
  report["report_frame"] = "working: x -> rotation x + translation (z up); every coordinate in this report is in it";
  report["output_frame"] = posed.outputs_in_input_frame ? "input" : "posed";
  return posed;
}

Mesh to_output_frame(const Mesh& mesh, const PosedInput& posed) {
  if (!posed.outputs_in_input_frame || posed.up.is_identity()) return mesh;
  return permute_axes(mesh, posed.up.inverse());
}

}  // namespace offsetopt::cli
