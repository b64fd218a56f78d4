// offsetopt optimize: the mission (Musialski et al. 2015): carve (and optionally thicken) the
// input with smooth offset surfaces so the printed solid meets a mass-property goal, verify the
// result and write the meshes and a JSON report (optimize/offset_optimization.h).
#include <chrono>
#include <cstdio>
#include <string>

#include "cli/cli_support.h"
#include "cli/progress_line.h"
#include "cli/commands.h"
#include "cli/optimize_report.h"
#include "cli/pose_options.h"
#include "cli/write_preview.h"
#include "io/json.h"
#include "meshio/load_input.h"
#include "meshio/write_mesh.h"
#include "optimize/offset_optimization.h"

namespace offsetopt::cli {

namespace {

const CommandHelp kHelp = {
    "usage: offsetopt optimize MESH --goal GOAL -o FILE [options]\n"
    "\n"
    "Carves an inner offset surface (and with --outer thickens the outside) so the printed solid\n"
    "meets GOAL, verifies the result on the final meshes and writes them. Lengths are in the\n"
    "mesh's units; 'diag' is its bounding-box diagonal. z is up; the object is never moved.\n"
    "\n"
    "goals:\n"
    "  stand          stands on its ground contact polygon, centre of mass low (paper eq. 5)\n"
    "  stand-filled   stands both empty and filled with --fill-density (eq. 6)\n"
    "  roly-poly      centre of mass under the centre of its hemispherical bottom (eq. 7)\n"
    "  spin           spins stably about z through its lowest point (eq. 8)\n"
    "  volume         the void holds --target-volume\n"
    "  float          floats fully submerged, upright, in --fluid-density (eq. 9)\n",
    {
        // Outputs. Every mesh output takes .obj, .stl, .ply or .3mf.
        {"-o, --output", "FILE", "none (required)", "a path ending in .obj, .stl, .ply or .3mf",
         "the printable solid: outer surface + reversed inner surface (welded into one closed surface with --fix); in a .3mf "
         "file one object holding every shell",
         "solid.3mf"},
        {"--report", "FILE", "none", "a path", "JSON report (parameters, properties before/after, goal metrics, constraints, "
         "solver statistics, verification, stage timings)", "report.json"},
        {"--no-timings", "", "off", "flag", "leave the timings out of the report so reruns are byte-identical", ""},
        {"--inner", "FILE", "none", "a mesh path", "the cavity written (its shells, outward-oriented)", "inner.obj"},
        {"--outer-mesh", "FILE", "none", "a mesh path", "the outer surface alone (the input itself without --outer)", "outer.obj"},
        {"--skeleton", "FILE", "none", "a mesh path", "the contracted meso-skeleton (same connectivity)", "skeleton.obj"},
        {"--preview", "FILE", "none", "a path ending in .svg",
         "an SVG picture of the result: sections, support polygon, centres of mass, the goal's figures (as 'offsetopt "
         "preview' draws it)",
         "picture.svg"},
        {"--unit", "UNIT", "the input's unit for a .3mf input, else millimeter", "micron | millimeter | centimeter | inch | foot | meter",
         "the unit written into .3mf outputs (the numbers are not scaled)", "inch"},
        // The problem.
        {"--goal", "GOAL", "none (required)", "stand | stand-filled | roly-poly | spin | volume | float", "one of the goals above",
         "stand"},
        {"--k", "N|all", "36", OptionRange::integer(1, 100000, " and below #V, or all"), "basis size; 'all' solves per vertex (paper eq. 1)", "12"},
        {"--basis", "KIND", "mass", "mass | laplacian", "mass: L phi = lambda M phi; laplacian: L phi = lambda phi", "laplacian"},
        {"--bounds", "MODE", "clamp", "clamp | hard",
         "clamp: bounds held by construction; hard: the paper's per-vertex linear constraints", "hard"},
        {"--outer", "", "off", "flag", "also optimise an outer offset (thickening, paper 4.1)", ""},
        {"--wall", "T", "0.01 diag", OptionRange::real(0, 1e12), "minimum wall thickness", "0.5"},
        {"--outer-max", "D", "0.02 diag", OptionRange::real(0, 1e12), "largest outer offset", "1"},
        {"--penalty", "WP", "1", OptionRange::real(0, 1e12), "weight of the outer offset's mean term", "2"},
        {"--margin", "E", "0.002 diag", OptionRange::real(0, 1e12),
         "stand: distance inside the support polygon; roly-poly, float: depth of the centre of mass below the centre", "0.1"},
        {"--fill-density", "R", "1", OptionRange::real(1e-6, 1e6), "stand-filled: density of the filling", "0.5"},
        {"--fluid-density", "R", "none (required for float)", OptionRange::real(1e-6, 0.999999), "float: fluid density relative to the material",
         "0.8"},
        {"--target-volume", "V", "none (required for volume)", OptionRange::real(1e-300, 1e36, " mesh units cubed"), "volume: the void's volume",
         "100"},
        {"--radius", "R", "sphere fitted to the bottom", OptionRange::real(1e-300, 1e12), "roly-poly: hemisphere radius", "20"},
        {"--fix", "REGION", "none", "x>V, x<V, y>V, y<V, z>V, z<V or sphere:X,Y,Z,R",
         "keep the surface (an opening) where REGION holds; with a contoured cavity and x/y/z>V or <V, a channel is cut "
         "from the cavity to the outside inside REGION (docs/printable-solid.md)",
         "z>50"},
        {"--opening", "REGION", "none", "x>V, x<V, y>V, y<V, z>V or z<V", "the same as --fix REGION", "z>230"},
        {"--drain-hole", "X,Y,Z[,R]", "none", "a point of the cavity, R > 0 (repeatable)",
         "a drain hole of radius R from the point through the nearest outer surface (contoured cavity)", "10,0,5,1.5"},
        {"--drain-holes", "auto", "none", "auto",
         "one drain hole per cavity shell, at its lowest point as posed, through the nearest wall", "auto"},
        {"--drain-hole-radius", "R", "2 (PrusaSlicer's 4 mm drain hole), at most 0.02 diag", OptionRange::real(1e-300, 1e12), "the drain holes' default radius",
         "1"},
        {"--ground-tol", "T", "0.001 diag", OptionRange::real(0, 1e12), "ground contact tolerance", "0.01"},
        {"--cavity", "MODE", "auto", "auto | offset | contour | quadric",
         "the cavity written: the inner offset surface (offset: the paper's, with repair rounds), the contoured implicit "
         "cavity (contour: closed, embedded, the wall kept exactly), the best void any carving reaches, bounded by a "
         "quadric (quadric), or auto: the offset surface when it verifies as it is, the contour otherwise, and the quadric "
         "void when the offset void misses a goal some void reaches or falls more than 1% short of the best",
         "contour"},
        {"--cavity-cells", "C", "1.5", OptionRange::real(1.25, 8), "contour grid cells per wall thickness", "3"},
        kPoseOptionSpecs[0],
        kPoseOptionSpecs[1],
        kPoseOptionSpecs[2],
        {"--no-repair-ring", "", "off", "flag",
         "--cavity offset: repairs tighten only the vertices on folds, not their one-ring too", ""},
        {"--threads", "N", "2", OptionRange::integer(1, 64),
         "threads per stage; 1 runs the stages one after another on one thread (lowest memory). The output is the same for "
         "any N.",
         "1"},
        {"--quiet", "", "off", "flag", "no progress on stderr", ""},
        {"-v, --verbose", "", "off", "flag", "also every outer iteration of the solver on stderr", ""},
        {"-h, --help", "", "off", "flag", "show this help", ""},
    },
    "exit codes: 0 goal met and verified; 2 bad input or usage; 3 ran, but the goal is not met\n"
    "or the result is invalid (outputs are still written; the report says why).\n"};

}  // namespace

const std::vector<OptionSpec>& optimize_options() { return kHelp.options; }

int run_optimize(const Args& args) {
  const auto start = std::chrono::steady_clock::now();
  ArgCursor cursor(args);
  std::string mesh_path, output, report_path, inner_path, outer_path, skeleton_path, preview_path, unit = "millimeter";
  bool quiet = false, timings_in_report = true, goal_given = false, unit_given = false;
  OptimizeOptions options = OptimizeOptions::defaults();
  PoseOptions pose_options;
  while (!cursor.done()) {
    const std::string& arg = cursor.next();
    require_known_option("optimize", kHelp.options, arg);
    if (arg == "--help" || arg == "-h") {
      write_text("-", format_help(kHelp));
      return kExitOk;
    } else if (arg == "-o" || arg == "--output") {
      output = cursor.value_of(arg);
    } else if (arg == "--report") {
      report_path = cursor.value_of(arg);
    } else if (arg == "--inner") {
      inner_path = cursor.value_of(arg);
    } else if (arg == "--outer-mesh") {
      outer_path = cursor.value_of(arg);
    } else if (arg == "--skeleton") {
      skeleton_path = cursor.value_of(arg);
    } else if (arg == "--preview") {
      preview_path = cursor.value_of(arg);
    } else if (arg == "--unit") {
      unit = parse_unit(cursor.value_of(arg));
      unit_given = true;
    } else if (arg == "--no-timings") {
      timings_in_report = false;
    } else if (arg == "--goal") {
      const std::string& name = cursor.value_of(arg);
      if (!parse_goal_kind(name, options.goal))
        throw UsageError("unknown goal '" + name + "' (stand, stand-filled, roly-poly, spin, volume, float)");
      goal_given = true;
    } else if (arg == "--k") {
      const std::string& value = cursor.value_of(arg);
      options.k = value == "all" ? 0 : parse_integer_option(kHelp.options, arg, value);
    } else if (arg == "--basis") {
      const std::string& value = cursor.value_of(arg);
      if (!parse_basis_kind(value, options.basis)) throw UsageError("--basis must be mass or laplacian, got '" + value + "'");
    } else if (arg == "--bounds") {
      const std::string& value = cursor.value_of(arg);
      if (value == "clamp") options.bounds = BoundsMode::clamp;
      else if (value == "hard") options.bounds = BoundsMode::hard;
      else throw UsageError("--bounds must be clamp or hard, got '" + value + "'");
    } else if (arg == "--outer") {
      options.outer = true;
    } else if (arg == "--wall") {
      options.wall = parse_real_option(kHelp.options, arg, cursor.value_of(arg));
    } else if (arg == "--outer-max") {
      options.outer_max = parse_real_option(kHelp.options, arg, cursor.value_of(arg));
    } else if (arg == "--penalty") {
      options.penalty = parse_real_option(kHelp.options, arg, cursor.value_of(arg));
    } else if (arg == "--margin") {
      options.margin = parse_real_option(kHelp.options, arg, cursor.value_of(arg));
    } else if (arg == "--fill-density") {
      options.fill_density = parse_real_option(kHelp.options, arg, cursor.value_of(arg));
    } else if (arg == "--fluid-density") {
      options.fluid_density = parse_real_option(kHelp.options, arg, cursor.value_of(arg));
    } else if (arg == "--target-volume") {
      options.target_volume = parse_real_option(kHelp.options, arg, cursor.value_of(arg));
    } else if (arg == "--radius") {
      options.radius = parse_real_option(kHelp.options, arg, cursor.value_of(arg));
    } else if (arg == "--fix" || arg == "--opening") {
      const std::string& value = cursor.value_of(arg);
      if (const std::string problem = parse_fix_region(value, options.fix); !problem.empty())
        throw UsageError(arg + ": " + problem);
    } else if (arg == "--drain-hole") {
      const std::string& value = cursor.value_of(arg);
      std::vector<double> numbers;
      std::size_t begin = 0;
      while (begin <= value.size()) {
        const std::size_t comma = value.find(',', begin);
        const std::size_t end = comma == std::string::npos ? value.size() : comma;
        numbers.push_back(parse_double(value.substr(begin, end - begin), arg, -1e12, 1e12));
        if (comma == std::string::npos) break;
        begin = comma + 1;
      }
      if (numbers.size() != 3 && numbers.size() != 4) throw UsageError("--drain-hole takes X,Y,Z or X,Y,Z,R, got '" + value + "'");
      DrainHoleRequest hole;
      hole.point = Eigen::Vector3d(numbers[0], numbers[1], numbers[2]);
      if (numbers.size() == 4) {
        if (!(numbers[3] > 0.0)) throw UsageError("--drain-hole: the radius must be > 0, got '" + value + "'");
        hole.radius = numbers[3];
      }
      options.drain_holes.push_back(hole);
    } else if (arg == "--drain-holes") {
      const std::string& value = cursor.value_of(arg);
      if (value != "auto") throw UsageError("--drain-holes takes 'auto', got '" + value + "'");
      options.drain_holes_auto = true;
    } else if (arg == "--drain-hole-radius") {
      options.drain_hole_radius = parse_real_option(kHelp.options, arg, cursor.value_of(arg));
    } else if (arg == "--cavity") {
      const std::string& value = cursor.value_of(arg);
      if (!parse_cavity_mode(value, options.cavity))
        throw UsageError("--cavity must be auto, offset, contour or quadric, got '" + value + "'");
    } else if (arg == "--cavity-cells") {
      options.cavity_cells_per_wall = parse_real_option(kHelp.options, arg, cursor.value_of(arg));
    } else if (arg == "--ground-tol") {
      options.ground_tol = parse_real_option(kHelp.options, arg, cursor.value_of(arg));
    } else if (arg == "--quiet") {
      quiet = true;
    } else if (arg == "--no-repair-ring") {
      options.repair_ring = false;
    } else if (arg == "--threads") {
      options.threads = parse_integer_option(kHelp.options, arg, cursor.value_of(arg));
    } else if (arg == "-v" || arg == "--verbose") {
      options.trace_solver = true;
    } else if (parse_pose_option(arg, cursor, pose_options)) {
    } else if (arg.size() > 1 && arg[0] == '-') {
      throw UsageError("unknown option '" + arg + "' for optimize (try 'offsetopt optimize --help')");
    } else if (mesh_path.empty()) {
      mesh_path = arg;
    } else {
      throw UsageError("optimize takes one mesh, got a second one '" + arg + "'");
    }
  }
  if (mesh_path.empty()) throw UsageError("optimize needs a mesh file (try 'offsetopt optimize --help')");
  if (!goal_given) throw UsageError("optimize needs --goal (stand, stand-filled, roly-poly, spin, volume, float)");
  if (output.empty()) throw UsageError("optimize needs an output file: -o FILE");
  if (options.goal == GoalKind::floating && options.fluid_density < 0)
    throw UsageError("--goal float needs --fluid-density R in (0, 1)");
  if (options.goal == GoalKind::volume && options.target_volume < 0)
    throw UsageError("--goal volume needs --target-volume V");
  for (const std::string* path : {&output, &report_path, &inner_path, &outer_path, &skeleton_path, &preview_path})
    if (!path->empty()) refuse_overwriting_input(*path, {mesh_path});
  // Verified as the files read back: float32 when any surface of the solid goes to an STL.
  for (const std::string* path : {&output, &inner_path, &outer_path})
    if (!path->empty() && stored_precision(*path) == StoredPrecision::float32) options.output_precision = StoredPrecision::float32;

  const auto load_start = std::chrono::steady_clock::now();
  LoadOptions load_options;
  load_options.single_component = true;  // one solid: one skeleton, one constant mode
  load_options.threads = options.threads;
  const InputMesh loaded = load_input(mesh_path, load_options);
  print_warnings(loaded.warnings, quiet);
  if (!unit_given && !loaded.unit.empty()) unit = loaded.unit;  // a 3MF input's unit carries over
  const double load_seconds = seconds_since(load_start);
  if (!quiet) std::fprintf(stderr, "load: %s, %ld vertices (%.2f s)\n", mesh_path.c_str(), static_cast<long>(loaded.mesh.V.rows()), load_seconds);

  // The live line (stage and fraction done) only on a terminal; the report and files do not
  // depend on it.
  ProgressLine live(!quiet && ProgressLine::stderr_is_terminal(), start);
  auto progress = [&](const std::string& line) {
    if (quiet) return;
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, " (%.2f s)", seconds_since(start));
    live.print_line(line + seconds);
  };
  options.on_stage_progress = [&live](const std::string& stage, double fraction) { live.update(stage, fraction); };
  const PosedInput posed = pose_input(loaded.mesh, pose_options, mesh_path, true);
  print_warnings(posed.warnings, quiet);
  options.flatten = pose_options.flatten;
  options.up = pose_options.up;
  options.posed_stable = pose_options.stable;
  // Searched once at the input boundary; a posed mesh is another mesh and is searched again.
  if (!pose_options.any()) options.input_self_intersections = loaded.self_intersections;
  OptimizeResult result = optimize_offsets(posed.mesh, options, progress);
  options.on_stage_progress = nullptr;
  live.clear();
  if (result.status == OptimizeStatus::bad_input) throw UsageError(mesh_path + ": " + result.message);
  print_warnings(result.warnings, quiet);

  const auto write_start = std::chrono::steady_clock::now();
  write_mesh(output, to_output_frame(result.printable, posed), unit);
  if (!inner_path.empty()) write_mesh(inner_path, to_output_frame(result.inner, posed), unit);
  if (!outer_path.empty()) write_mesh(outer_path, to_output_frame(result.outer, posed), unit);
  if (!skeleton_path.empty()) write_mesh(skeleton_path, to_output_frame(result.skeleton, posed), unit);
  Json report = Json::object();
  report["input"] = mesh_path;
  report["format"] = loaded.format;
  report["vertices"] = static_cast<long long>(loaded.mesh.V.rows());
  report["faces"] = static_cast<long long>(loaded.mesh.F.rows());
  if (pose_options.any()) report["pose"] = posed.report;
  const Json run_report = optimize_report(options, result);
  for (const auto& item : run_report.items()) report[item.first] = item.second;
  Json outputs = Json::object();
  outputs["solid"] = output;
  outputs["inner"] = inner_path.empty() ? Json() : Json(inner_path);
  outputs["outer"] = outer_path.empty() ? Json() : Json(outer_path);
  outputs["skeleton"] = skeleton_path.empty() ? Json() : Json(skeleton_path);
  report["outputs"] = outputs;
  Json timings = stage_timings_json(result.timings);
  timings["load"] = load_seconds;
  timings["write"] = seconds_since(write_start);
  if (timings_in_report) report["timings"] = timings;
  if (!report_path.empty()) write_text(report_path, report.dump(2), {mesh_path});
  if (!preview_path.empty()) write_preview(preview_path, result.printable, report, "the report", {mesh_path});
  if (!quiet) {
    std::fprintf(stderr, "stages:");
    for (const auto& item : timings.items()) std::fprintf(stderr, " %s %.3f s;", item.first.c_str(), item.second.as_number());
    std::fprintf(stderr, "\n");
  }
  if (result.status != OptimizeStatus::verified) {
    std::fprintf(stderr, "Error: goal not met: %s\n", result.message.c_str());
    return kExitGoalNotMet;
  }
  if (!quiet) std::fprintf(stderr, "done: goal '%s' met and verified\n", to_string(options.goal));
  return kExitOk;
}

}  // namespace offsetopt::cli
