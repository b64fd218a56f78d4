// offsetopt inspect: mass properties (paper eq. 4) and static stability of the solid as is.
#include <cmath>
#include <cstdio>
#include <string>

#include "cli/cli_support.h"
#include "cli/commands.h"
#include "cli/pose_options.h"
#include "io/json.h"
#include "mass/mass_properties.h"
#include "mass/stability.h"
#include "mass/surface_area.h"
#include "mass/volume_integrals.h"
#include "meshio/load_mesh.h"
#include "util/format_double.h"

namespace offsetopt::cli {

namespace {

const CommandHelp kHelp = {
    "usage: offsetopt inspect MESH [--json FILE|-] [--ground-tol T] [--up AXIS] [--pose as-is|stable]\n"
    "                                [--flatten H]\n"
    "\n"
    "Mass properties (density 1: mass = volume; inertia about the centre of mass,\n"
    "Ixy = -integral (x-cx)(y-cy) dV) and static stability of the solid bounded by MESH\n"
    "as posed (z up, resting on its lowest vertices).\n",
    {
        {"--json", "FILE|-", "none (a readable summary goes to stdout)", "a path, or - for stdout",
         "write the report as JSON to FILE, or to stdout with '-'", "-"},
        {"--ground-tol", "T", "1e-3 x the bounding-box diagonal", OptionRange::real(0, 1e9, " mesh units"),
         "vertices with z <= zmin + T touch the ground", "0.01"},
        kPoseOptionSpecs[0],
        kPoseOptionSpecs[1],
        kPoseOptionSpecs[2],
        {"-h, --help", "", "off", "flag", "show this help", ""},
    },
    ""};

// Six significant digits for people; the JSON report carries the full round-trip values.
std::string text(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", value == 0.0 ? 0.0 : value);
  return buffer;
}

std::string triple(const Eigen::Vector3d& v) { return "(" + text(v.x()) + ", " + text(v.y()) + ", " + text(v.z()) + ")"; }

}  // namespace

int run_inspect(const Args& args) {
  ArgCursor cursor(args);
  std::string mesh_path, json_path;
  StabilityOptions stability_options;
  bool json_requested = false;
  PoseOptions pose_options;
  while (!cursor.done()) {
    const std::string& arg = cursor.next();
    require_known_option("inspect", kHelp.options, arg);
    if (arg == "--help" || arg == "-h") {
      write_text("-", format_help(kHelp));
      return kExitOk;
    } else if (arg == "--json") {
      json_path = cursor.value_of(arg);
      json_requested = true;
    } else if (arg == "--ground-tol") {
      stability_options.ground_tol = parse_real_option(kHelp.options, arg, cursor.value_of(arg));
    } else if (parse_pose_option(arg, cursor, pose_options)) {
    } else if (arg.size() > 1 && arg[0] == '-') {
      throw UsageError("unknown option '" + arg + "' for inspect (try 'offsetopt inspect --help')");
    } else if (mesh_path.empty()) {
      mesh_path = arg;
    } else {
      throw UsageError("inspect takes one mesh, got a second one '" + arg + "'");
    }
  }
  if (mesh_path.empty()) throw UsageError("inspect needs a mesh file (try 'offsetopt inspect --help')");

  const LoadedMesh loaded = load_input(mesh_path);
  print_warnings(loaded.warnings);
  const PosedInput posed = pose_input(loaded.mesh, pose_options, mesh_path, false);
  print_warnings(posed.warnings);
  const Mesh& mesh = posed.mesh;
  const VolumeIntegrals integrals = volume_integrals(mesh);
  const double volume = integrals.values(kIntVolume);
  if (!(volume > 0.0) || !std::isfinite(volume))
    throw MeshInputError(mesh_path + ": the surface encloses no positive volume (signed volume " + format_double(volume) + ")");

  const Vector10d P = mass_properties(integrals);
  const Eigen::Vector3d com = P.segment<3>(kCx);
  const PrincipalInertia principal = principal_inertia(P);
  const Eigen::Vector3d lo = mesh.V.colwise().minCoeff().transpose(), hi = mesh.V.colwise().maxCoeff().transpose();
  const double area = surface_area(mesh);
  const Stability stability = compute_stability(mesh, com, stability_options);

  if (json_requested) {
    Json report = Json::object();
    report.set("input", mesh_path);
    report.set("vertices", static_cast<long long>(mesh.V.rows()));
    report.set("faces", static_cast<long long>(mesh.F.rows()));
    report.set("area", area);
    report.set("volume", volume);
    report.set("center_of_mass", vec3(com));
    Json inertia = Json::object();
    inertia.set("xx", P(kIxx));
    inertia.set("yy", P(kIyy));
    inertia.set("zz", P(kIzz));
    inertia.set("xy", P(kIxy));
    inertia.set("yz", P(kIyz));
    inertia.set("zx", P(kIzx));
    report.set("inertia", inertia);
    report.set("principal_moments", vec3(principal.moments));
    Json axes = Json::array();
    for (int k = 0; k < 3; ++k) axes.push_back(vec3(principal.axes.col(k)));
    report.set("principal_axes", axes);
    Json bbox = Json::object();
    bbox.set("min", vec3(lo));
    bbox.set("max", vec3(hi));
    report.set("bbox", bbox);
    Json stand = Json::object();
    stand.set("ground_z", stability.ground_z);
    stand.set("ground_tol", stability.ground_tol);
    stand.set("contact_vertices", stability.contact_vertex_count);
    Json polygon = Json::array();
    for (const auto& p : stability.support_polygon) polygon.push_back(Json::array_of({p.x(), p.y()}));
    stand.set("support_polygon", polygon);
    stand.set("com_margin", stability.com_margin);
    stand.set("tipping_angle_deg", stability.tipping_angle_deg);
    stand.set("tipping_edge", stability.tipping_edge);
    stand.set("stands", stability.stands);
    report.set("stability", stand);
    if (pose_options.any()) report.set("pose", posed.report);
    write_text(json_path, report.dump(2) + "\n", {mesh_path});
    return kExitOk;
  }

  std::string out;
  out += mesh_path + ": " + std::to_string(mesh.V.rows()) + " vertices, " + std::to_string(mesh.F.rows()) + " faces\n";
  if (pose_options.any()) {
    const Json& pose = posed.report;
    out += "  pose               up " + pose_options.up;
    if (pose_options.stable) out += ", resting on its most stable hull face (margin " + text(pose.at("stable").at("margin").as_number()) + ")";
    if (pose_options.flatten > 0.0)
      out += ", base cut at z = " + text(pose.at("flatten").at("plane_z").as_number()) + " (" +
             std::to_string(pose.at("flatten").at("cap_loops").as_integer()) + " cap loops)";
    out += "; figures below in the turned frame\n";
  }
  out += "  area               " + text(area) + "\n";
  out += "  volume (= mass)    " + text(volume) + "\n";
  out += "  centre of mass     " + triple(com) + "\n";
  out += "  inertia about the centre of mass\n";
  out += "    Ixx Iyy Izz      " + text(P(kIxx)) + "  " + text(P(kIyy)) + "  " + text(P(kIzz)) + "\n";
  out += "    Ixy Iyz Izx      " + text(P(kIxy)) + "  " + text(P(kIyz)) + "  " + text(P(kIzx)) + "\n";
  out += "  principal moments  " + triple(principal.moments) + "\n";
  for (int k = 0; k < 3; ++k) out += "    axis " + std::to_string(k) + "           " + triple(principal.axes.col(k)) + "\n";
  out += "  bounding box       " + triple(lo) + " - " + triple(hi) + "\n";
  out += "  ground             z = " + text(stability.ground_z) + ", tolerance " + text(stability.ground_tol) + ", " +
         std::to_string(stability.contact_vertex_count) + " contact vertices, support polygon of " +
         std::to_string(stability.support_polygon.size()) + " points\n";
  out += "  com margin         " + text(stability.com_margin) + " (positive inside the support polygon)\n";
  out += "  tipping angle      " + text(stability.tipping_angle_deg) + " deg\n";
  out += std::string("  stands             ") + (stability.stands ? "yes" : "no, it falls over") + "\n";
  write_text("-", out);
  return kExitOk;
}

}  // namespace offsetopt::cli
