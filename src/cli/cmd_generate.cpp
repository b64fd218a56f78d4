// offsetopt generate: write one of the procedural demo meshes (mesh/demo_meshes.h).
#include <cstdio>
#include <stdexcept>
#include <string>

#include "cli/cli_support.h"
#include "cli/commands.h"
#include "mesh/demo_meshes.h"
#include "meshio/load_mesh.h"
#include "meshio/write_mesh.h"

namespace offsetopt::cli {

namespace {

const CommandHelp kHelp = {
    "usage: offsetopt generate NAME -o FILE [--detail D] [--unit UNIT]\n"
    "       offsetopt generate --list\n"
    "\n"
    "Writes a procedural demo mesh (deterministic: the same bytes on every machine), z up,\n"
    "resting on z = 0, in millimetres. The format follows FILE's extension (.obj, .stl, .ply,\n"
    ".3mf); '-o -' writes OBJ to stdout.\n",
    {
        {"-o, --output", "FILE", "none (required)", "a path ending in .obj, .stl, .ply or .3mf, or -",
         "where to write the mesh", "demo.obj"},
        {"--detail", "D", "1", OptionRange::real(0.25, 32),
         "multiply the ring and segment counts by D (bottle, top, rolypoly and buoy only): about D^2 times the vertices, for benchmarks",
         "2"},
        {"--unit", "UNIT", "millimeter", "micron | millimeter | centimeter | inch | foot | meter",
         "the unit written into a .3mf file (the numbers are not scaled)", "millimeter"},
        {"--list", "", "off", "flag", "print the available names, one per line", ""},
        {"-h, --help", "", "off", "flag", "show this help", ""},
    },
    ""};

}  // namespace

int run_generate(const Args& args) {
  ArgCursor cursor(args);
  std::string name, output;
  bool list = false;
  double detail = 1.0;
  std::string unit = "millimeter";
  while (!cursor.done()) {
    const std::string& arg = cursor.next();
    require_known_option("generate", kHelp.options, arg);
    if (arg == "--help" || arg == "-h") {
      write_text("-", format_help(kHelp));
      return kExitOk;
    } else if (arg == "--list") {
      list = true;
    } else if (arg == "-o" || arg == "--output") {
      output = cursor.value_of(arg);
    } else if (arg == "--unit") {
      unit = parse_unit(cursor.value_of(arg));
    } else if (arg == "--detail") {
      detail = parse_real_option(kHelp.options, arg, cursor.value_of(arg));
    } else if (arg.size() > 1 && arg[0] == '-') {
      throw UsageError("unknown option '" + arg + "' for generate (try 'offsetopt generate --help')");
    } else if (name.empty()) {
      name = arg;
    } else {
      throw UsageError("generate takes one name, got a second one '" + arg + "'");
    }
  }
  if (list) {
    std::string out;
    for (const auto& n : demo_mesh_names()) out += n + "\n";
    write_text("-", out);
    return kExitOk;
  }
  if (name.empty()) throw UsageError("generate needs a mesh name (see 'offsetopt generate --list')");
  bool known = false;
  for (const auto& n : demo_mesh_names()) known = known || n == name;
  if (!known) throw UsageError("unknown demo mesh '" + name + "' (see 'offsetopt generate --list')");
  if (output.empty()) throw UsageError("generate needs an output file: -o FILE");

  Mesh mesh;
  try {
    mesh = make_demo_mesh(name, detail);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--detail: ") + e.what());  // the name is known: only detail is left
  }
  if (output == "-") {
    write_text("-", mesh_to_bytes(".obj", mesh));
    return kExitOk;
  }
  try {
    write_mesh(output, mesh, unit);
  } catch (const MeshInputError&) {
    throw;  // unsupported extension: already one line naming the problem
  } catch (const std::runtime_error& e) {
    throw UsageError(e.what());
  }
  return kExitOk;
}

}  // namespace offsetopt::cli
