// offsetopt skeleton: the meso-skeleton by Laplacian contraction (skeleton/laplacian_contraction.h)
// written as a mesh with the input's connectivity, and the offset field built on it
// (shape/offset_field.h) summarised in a JSON report.
#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "cli/cli_support.h"
#include "cli/commands.h"
#include "geometry/bvh.h"
#include "io/json.h"
#include "meshio/load_mesh.h"
#include "meshio/write_mesh.h"
#include "shape/offset_field.h"
#include "skeleton/laplacian_contraction.h"

namespace offsetopt::cli {

namespace {

const CommandHelp kHelp = {
    "usage: offsetopt skeleton MESH -o FILE [--json FILE|-] [--wall T] [--max-steps N] [--quiet]\n"
    "\n"
    "Contracts MESH by constrained Laplacian smoothing (Au et al. 2008) to its meso-skeleton\n"
    "and writes it with the same vertices order and faces (vertex i of FILE is where vertex i\n"
    "of MESH went). The offset directions and bounds built on it are summarised in the report.\n",
    {
        {"-o, --output", "FILE", "none (required)", "a path ending in .obj, .stl, .ply or .3mf, or - (OBJ to stdout)",
         "where to write the contracted mesh", "skeleton.obj"},
        {"--json", "FILE|-", "none", "a path, or - for stdout", "write statistics as JSON to FILE, or to stdout with '-'",
         "stats.json"},
        {"--wall", "T", "0", OptionRange::real(0, 1e12, " mesh units"),
         "wall thickness for the lower offset bounds; the report then counts vertices whose bound band is empty", "0.5"},
        {"--max-steps", "N", "8", OptionRange::integer(1, 100),
         "contraction step cap; the run stops earlier once the enclosed volume is at most 10% of the input's", "4"},
        {"--unit", "UNIT", "the input's unit for a .3mf input, else millimeter", "micron | millimeter | centimeter | inch | foot | meter",
         "the unit written into a .3mf output (the numbers are not scaled)", "millimeter"},
        {"--quiet", "", "off", "flag", "no progress on stderr", ""},
        {"-h, --help", "", "off", "flag", "show this help", ""},
    },
    ""};

}  // namespace

int run_skeleton(const Args& args) {
  const auto start = std::chrono::steady_clock::now();
  ArgCursor cursor(args);
  std::string mesh_path, output, json_path, unit = "millimeter";
  bool quiet = false, unit_given = false;
  ContractionOptions contraction_options;
  OffsetFieldOptions field_options;
  while (!cursor.done()) {
    const std::string& arg = cursor.next();
    require_known_option("skeleton", kHelp.options, arg);
    if (arg == "--help" || arg == "-h") {
      write_text("-", format_help(kHelp));
      return kExitOk;
    } else if (arg == "-o" || arg == "--output") {
      output = cursor.value_of(arg);
    } else if (arg == "--json") {
      json_path = cursor.value_of(arg);
    } else if (arg == "--wall") {
      field_options.wall = parse_real_option(kHelp.options, arg, cursor.value_of(arg));
    } else if (arg == "--unit") {
      unit = parse_unit(cursor.value_of(arg));
      unit_given = true;
    } else if (arg == "--max-steps") {
      contraction_options.max_steps = parse_integer_option(kHelp.options, arg, cursor.value_of(arg));
    } else if (arg == "--quiet") {
      quiet = true;
    } else if (arg.size() > 1 && arg[0] == '-') {
      throw UsageError("unknown option '" + arg + "' for skeleton (try 'offsetopt skeleton --help')");
    } else if (mesh_path.empty()) {
      mesh_path = arg;
    } else {
      throw UsageError("skeleton takes one mesh, got a second one '" + arg + "'");
    }
  }
  if (mesh_path.empty()) throw UsageError("skeleton needs a mesh file (try 'offsetopt skeleton --help')");
  if (output.empty()) throw UsageError("skeleton needs an output file: -o FILE");
  if (output == "-" && json_path == "-") throw UsageError("-o - and --json - would both write to stdout; send one to a file");
  refuse_overwriting_input(output, {mesh_path});
  if (!json_path.empty()) refuse_overwriting_input(json_path, {mesh_path});
  if (output != "-") {
    // Refuse an unsupported output format before the work, not after it.
    const std::size_t slash = output.find_last_of('/'), dot = output.find_last_of('.');
    const bool has_extension = dot != std::string::npos && (slash == std::string::npos || dot > slash);
    (void)mesh_to_bytes(has_extension ? output.substr(dot) : "", Mesh{});
  }

  const LoadedMesh loaded = load_input(mesh_path);
  print_warnings(loaded.warnings, quiet);
  if (!unit_given && !loaded.unit.empty()) unit = loaded.unit;  // a 3MF input's unit carries over
  const Mesh& mesh = loaded.mesh;

  const auto skeleton_start = std::chrono::steady_clock::now();
  const ContractionResult contraction = laplacian_contraction(mesh.V, mesh.F, contraction_options);
  const double skeleton_seconds = seconds_since(skeleton_start);
  if (!quiet)
    std::fprintf(stderr, "skeleton: %d steps (%s), area ratio %.4g, volume ratio %.4g, %.3f s\n", contraction.steps,
                 to_string(contraction.status), contraction.area_ratio, contraction.volume_ratio, skeleton_seconds);

  const auto field_start = std::chrono::steady_clock::now();
  const TriangleBvh bvh(mesh.V, mesh.F);
  const OffsetField field = offset_field(mesh, contraction.V, bvh, field_options);
  const double field_seconds = seconds_since(field_start);
  int band_empty = 0;
  double upper_min = 0.0, upper_max = 0.0;
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    if (field.lower[i] > field.upper[i]) ++band_empty;
    upper_min = i == 0 ? field.upper[i] : std::min(upper_min, field.upper[i]);
    upper_max = i == 0 ? field.upper[i] : std::max(upper_max, field.upper[i]);
  }
  if (!quiet)
    std::fprintf(stderr, "offset field: %d shortened, %d along -n (%d shallow skeleton, %d immobile), %.3f s\n",
                 field.shortened_count, field.fallback_count, field.shallow_count, field.immobile_count, field_seconds);

  Mesh skeleton;
  skeleton.V = contraction.V;
  skeleton.F = mesh.F;
  if (output == "-") {
    write_text("-", mesh_to_bytes(".obj", skeleton));
  } else {
    try {
      write_mesh(output, skeleton, unit);
    } catch (const MeshInputError&) {
      throw;
    } catch (const std::runtime_error& e) {
      throw UsageError(e.what());
    }
  }

  if (!json_path.empty()) {
    Json report = Json::object();
    report.set("input", mesh_path);
    report.set("output", output);
    report.set("vertices", static_cast<long long>(mesh.V.rows()));
    report.set("faces", static_cast<long long>(mesh.F.rows()));
    Json parameters = Json::object();
    parameters.set("initial_laplacian_weight", contraction_options.initial_laplacian_weight);
    parameters.set("laplacian_weight_growth", contraction_options.laplacian_weight_growth);
    parameters.set("attraction_weight", contraction_options.attraction_weight);
    parameters.set("stop_volume_ratio", contraction_options.stop_volume_ratio);
    parameters.set("max_steps", contraction_options.max_steps);
    parameters.set("cotan_sine_floor", contraction_options.cotan_sine_floor);
    parameters.set("area_ratio_floor", contraction_options.area_ratio_floor);
    parameters.set("wall", field_options.wall);
    parameters.set("thickness_cosine_floor", field_options.thickness_cosine_floor);
    parameters.set("min_inward_cosine", field_options.min_inward_cosine);
    parameters.set("exit_fraction", field_options.exit_fraction);
    parameters.set("shallow_fraction", field_options.shallow_fraction);
    report.set("parameters", parameters);
    Json skeleton_json = Json::object();
    skeleton_json.set("status", to_string(contraction.status));
    skeleton_json.set("steps", contraction.steps);
    skeleton_json.set("area_ratio", contraction.area_ratio);
    skeleton_json.set("volume_ratio", contraction.volume_ratio);
    skeleton_json.set("ordering", contraction.ordering);
    skeleton_json.set("predicted_factor_nonzeros", contraction.predicted_factor_nonzeros);
    Json history = Json::array();
    for (const ContractionStep& step : contraction.history) {
      Json s = Json::object();
      s.set("laplacian_weight", step.laplacian_weight);
      s.set("area_ratio", step.area_ratio);
      s.set("volume_ratio", step.volume_ratio);
      history.push_back(s);
    }
    skeleton_json.set("history", history);
    report.set("skeleton", skeleton_json);
    Json field_json = Json::object();
    field_json.set("shortened", field.shortened_count);
    field_json.set("fallback", field.fallback_count);
    field_json.set("shallow", field.shallow_count);
    field_json.set("immobile", field.immobile_count);
    field_json.set("upper_min", upper_min);
    field_json.set("upper_max", upper_max);
    if (field_options.wall > 0.0) field_json.set("band_empty", band_empty);
    report.set("offset_field", field_json);
    report.set("seconds", skeleton_seconds);
    report.set("offset_field_seconds", field_seconds);
    report.set("total_seconds", seconds_since(start));
    write_text(json_path, report.dump(2) + "\n", {mesh_path});
  }
  if (contraction.status == ContractionStatus::factorization_failed) {
    std::fprintf(stderr, "Warning: the contraction stopped after %d steps: the factorisation failed; the output holds the last good step\n",
                 contraction.steps);
    return kExitGoalNotMet;
  }
  return kExitOk;
}

}  // namespace offsetopt::cli
