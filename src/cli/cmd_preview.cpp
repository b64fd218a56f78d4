// offsetopt preview: the picture of a result already written by `optimize` (issue 14): the solid
// is read in any supported format, the goal and its parameters come from the optimize report, the
// rest (sections, stability, waterline, moments) is recomputed from the solid
// (optimize/preview_svg.h).
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "cli/cli_support.h"
#include "cli/commands.h"
#include "cli/write_preview.h"
#include "io/json.h"
#include "meshio/load_mesh.h"

namespace offsetopt::cli {

namespace {

const CommandHelp kHelp = {
    "usage: offsetopt preview SOLID --report REPORT -o FILE.svg [--quiet]\n"
    "\n"
    "Draws a result of 'offsetopt optimize' as a self-contained SVG, to scale: the cross-sections\n"
    "through the centre of mass (xz and yz) with material, cavity and wall; a top view with the\n"
    "support polygon, the margin and the centre of mass before and after; and what the goal needs\n"
    "(tipping angle, sphere centre, spin axis and moments, waterline and centre of buoyancy, void\n"
    "volume). 'optimize --preview FILE.svg' draws the same picture right after a run. SOLID is the\n"
    "printable solid optimize wrote (.obj, .stl, .off, .ply, .3mf).\n",
    {
        {"--report", "REPORT", "none (required)", "a path",
         "the JSON report optimize wrote for it: goal, parameters, the input's centre of mass", "report.json"},
        {"-o, --output", "FILE", "none (required)", "a path, or - for stdout", "the SVG to write", "picture.svg"},
        {"--quiet", "", "off", "flag", "no warnings on stderr", ""},
        {"-h, --help", "", "off", "flag", "show this help", ""},
    },
    ""};

}  // namespace

int run_preview(const Args& args) {
  ArgCursor cursor(args);
  std::string solid_path, report_path, output;
  bool quiet = false;
  while (!cursor.done()) {
    const std::string& arg = cursor.next();
    require_known_option("preview", kHelp.options, arg);
    if (arg == "--help" || arg == "-h") {
      write_text("-", format_help(kHelp));
      return kExitOk;
    } else if (arg == "-o" || arg == "--output") {
      output = cursor.value_of(arg);
    } else if (arg == "--report") {
      report_path = cursor.value_of(arg);
    } else if (arg == "--quiet") {
      quiet = true;
    } else if (arg.size() > 1 && arg[0] == '-') {
      throw UsageError("unknown option '" + arg + "' for preview (try 'offsetopt preview --help')");
    } else if (solid_path.empty()) {
      solid_path = arg;
    } else {
      throw UsageError("preview takes one solid, got a second one '" + arg + "'");
    }
  }
  if (solid_path.empty()) throw UsageError("preview needs a solid mesh file (try 'offsetopt preview --help')");
  if (report_path.empty()) throw UsageError("preview needs the optimize report: --report REPORT");
  if (output.empty()) throw UsageError("preview needs an output file: -o FILE.svg");
  refuse_overwriting_input(output, {solid_path, report_path});

  std::ifstream in(report_path, std::ios::binary);
  if (!in) throw UsageError("cannot read the report " + report_path);
  std::ostringstream text;
  text << in.rdbuf();
  Json report;
  try {
    report = Json::parse(text.str());
  } catch (const std::runtime_error& e) {
    throw UsageError(std::string("the report is not valid JSON (") + e.what() + "), " + report_path);
  }
  const LoadedMesh loaded = load_mesh(solid_path);  // several shells allowed: outer and cavities
  // A solid with cavities is several shells by design; only other warnings are worth printing.
  for (const std::string& w : loaded.warnings)
    if (!quiet && w.find("separate closed shells") == std::string::npos) std::fprintf(stderr, "Warning: %s\n", w.c_str());
  write_preview(output, loaded.mesh, report, report_path, {solid_path, report_path});
  return kExitOk;
}

}  // namespace offsetopt::cli
