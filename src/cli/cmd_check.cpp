// offsetopt check MESH [--quiet]: validate a mesh as a printable solid. Reports the file as it
// is (no repairs): one "Error: ..." line per defect on stderr and exit 2, or a summary line on
// stdout and exit 0 for a closed, oriented, connected 2-manifold of positive volume.
#include <cstdio>

#include "cli/cli_support.h"
#include "cli/commands.h"
#include "geometry/mesh_defects.h"
#include "meshio/read_raw_mesh.h"
#include "meshio/validate_mesh.h"
#include "util/format_double.h"

namespace offsetopt::cli {

namespace {

const CommandHelp kHelp = {
    "usage: offsetopt check MESH [--quiet]\n"
    "\n"
    "Validate MESH (.obj, .stl, .off, .ply, .3mf) as a printable solid. Each defect is one line on\n"
    "stderr: 'Error: <file>: <defect>: <count> (first: face N[, line L]): <details>'.\n"
    "Checks: empty mesh, non-finite or too large coordinates, vertex indices out of range,\n"
    "degenerate and duplicate faces, boundary edges, non-manifold edges and vertices,\n"
    "inconsistent orientation, zero volume, inside-out shells, several components,\n"
    "self-intersecting face pairs and pinches (distinct vertices at one position; looked\n"
    "for once the surface is closed and edge-manifold).\n"
    "Zero-area faces with three distinct collinear corners are a warning, not a defect.\n"
    "Faces and vertices are numbered from 0 in file order (faces after triangulation).\n",
    {
        {"-q, --quiet", "", "off", "flag", "no warnings and no summary line; errors and the exit code only", ""},
        {"-h, --help", "", "off", "flag", "show this help", ""},
    },
    "exit codes: 0 closed, oriented, connected 2-manifold of positive volume (summary on\n"
    "stdout); 2 any defect, unreadable file or bad usage\n"};

}  // namespace

int run_check(const Args& args) {
  std::string path;
  bool quiet = false;
  ArgCursor cursor(args);
  while (!cursor.done()) {
    const std::string& arg = cursor.next();
    require_known_option("check", kHelp.options, arg);
    if (arg == "--help" || arg == "-h") {
      write_text("-", format_help(kHelp));
      return kExitOk;
    }
    if (arg == "--quiet" || arg == "-q") {
      quiet = true;
    } else if (!arg.empty() && arg[0] == '-' && arg != "-") {
      throw UsageError("check: unknown option '" + arg + "' (try 'offsetopt check --help')");
    } else if (path.empty()) {
      path = arg;
    } else {
      throw UsageError("check: more than one mesh given ('" + path + "', '" + arg + "')");
    }
  }
  if (path.empty()) throw UsageError("check: no mesh given (usage: offsetopt check MESH [--quiet])");

  const RawMesh raw = read_raw_mesh(path);  // unreadable input: MeshInputError, exit 2 in main
  std::vector<std::string> warnings;
  for (const std::string& w : raw.warnings) warnings.push_back(path + ": " + w);
  const Mesh mesh{raw.V, raw.F};
  const MeshValidation validation = validate_mesh(mesh);
  if (validation.unreferenced_vertices > 0) {
    warnings.push_back(path + ": " + std::to_string(validation.unreferenced_vertices) + " unreferenced " +
                       (validation.unreferenced_vertices == 1 ? "vertex" : "vertices") + " (first: vertex " +
                       std::to_string(validation.first_unreferenced) + "); load_mesh drops them");
  }
  if (validation.zero_area_faces > 0) {
    std::string where = "face " + std::to_string(validation.first_zero_area_face);
    if (static_cast<std::size_t>(validation.first_zero_area_face) < raw.face_line.size())
      where += ", line " + std::to_string(raw.face_line[static_cast<std::size_t>(validation.first_zero_area_face)]);
    warnings.push_back(path + ": " + std::to_string(validation.zero_area_faces) +
                       (validation.zero_area_faces == 1 ? " zero-area face" : " zero-area faces") +
                       " with three distinct collinear corners (first: " + where +
                       "); accepted: they add nothing to the volume");
  }
  print_warnings(warnings, quiet);
  const DefectSource source{nullptr, nullptr, &raw.face_line, &raw.vertex_line};
  for (const Defect& defect : validation.defects)
    std::fprintf(stderr, "Error: %s\n", defect_report_line(path, defect, source).c_str());
  // Crossings and pinches are looked for on a closed, edge-manifold surface only: elsewhere "where
  // the mesh joins two faces" is not defined (a duplicate face would count again as a pair), and
  // the defects above already refuse the file. Shells that are inside-out, overlap or are several
  // are still searched: crossings are what makes them overlap.
  bool geometry_ok = true;
  for (const Defect& d : validation.defects)
    geometry_ok = geometry_ok && (d.kind == DefectKind::several_components || d.kind == DefectKind::inside_out ||
                                  d.kind == DefectKind::overlapping_shells || d.kind == DefectKind::zero_volume);
  bool geometric_defect = false;
  if (geometry_ok) {
    const SelfIntersectionReport crossings = find_self_intersections(mesh);
    if (crossings.work_cap_reached && !quiet)
      std::fprintf(stderr, "Warning: %s: self-intersection search stopped at its work cap (%lld candidate face pairs)\n",
                   path.c_str(), crossings.candidate_pairs);
    if (crossings.pairs > 0) {
      std::fprintf(stderr, "Error: %s: %s\n", path.c_str(), describe_self_intersections(crossings, {}, raw.face_line).c_str());
      geometric_defect = true;
    }
    const PinchReport pinches = find_pinches(mesh);
    if (pinches.pairs > 0) {
      std::fprintf(stderr, "Error: %s: %s\n", path.c_str(), describe_pinches(pinches, {}, raw.vertex_line).c_str());
      geometric_defect = true;
    }
  }
  if (!validation.valid() || geometric_defect) return kExitBadInput;
  if (!quiet) {
    std::string summary = path + ": ok: " + format_name(raw.format) + ", " + std::to_string(validation.vertices) +
                          " vertices, " + std::to_string(validation.faces) + " faces, " +
                          std::to_string(validation.edges) + " edges, " + std::to_string(validation.components) +
                          (validation.components == 1 ? " component" : " components") + ", genus " +
                          std::to_string(validation.genus) + ", volume ";
    append_double(summary, validation.volume);
    std::printf("%s\n", summary.c_str());
  }
  return kExitOk;
}

}  // namespace offsetopt::cli
