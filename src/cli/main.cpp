// offsetopt: carve and thicken closed meshes with smooth offset surfaces so the printed object
// meets a mass-property goal (Musialski et al. 2015, "Reduced-Order Shape Optimization Using
// Offset Surfaces"). This file only dispatches to the subcommands.
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>

#include <Eigen/Core>

#include "cli/cli_support.h"
#include "cli/commands.h"
#include "cli/process_heap.h"
#include "meshio/load_mesh.h"
#include "util/deterministic_eigen.h"

namespace {

void print_usage(std::FILE* out) {
  std::fputs(
      "offsetopt " OFFSETOPT_VERSION " - reduced-order shape optimisation with offset surfaces\n"
      "\n"
      "usage: offsetopt COMMAND [options]\n"
      "\n"
      "commands:\n"
      "  check    MESH                 validate a mesh; diagnostics on stderr\n"
      "  inspect  MESH [--json FILE|-] mass properties and stability as is\n"
      "  basis    MESH --k N           manifold-harmonic eigenpairs\n"
      "  skeleton MESH -o FILE         meso-skeleton with the same connectivity\n"
      "  optimize MESH --goal GOAL -o FILE   carve/thicken to meet a goal\n"
      "  preview  SOLID --report REPORT -o FILE.svg   picture of a result\n"
      "  generate NAME -o FILE         write a demo mesh\n"
      "  batch    MANIFEST.tsv [--jobs N]   optimize every line of a manifest, resumable\n"
      "\n"
      "'offsetopt COMMAND --help' lists a command's options.\n"
      "exit codes: 0 done, 1 internal error, 2 bad input or usage, 3 goal not met\n",
      out);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace offsetopt::cli;
  offsetopt::use_deterministic_eigen_blocking();
  offsetopt::cli::set_up_process_heap();
  if (argc < 2) {
    print_usage(stderr);
    return kExitBadInput;
  }
  const char* command = argv[1];
  if (!std::strcmp(command, "--help") || !std::strcmp(command, "-h") || !std::strcmp(command, "help")) {
    print_usage(stdout);
    return kExitOk;
  }
  if (!std::strcmp(command, "--version")) {
    std::printf("offsetopt %s\nbuild: %s, Eigen %d.%d.%d\n", OFFSETOPT_VERSION, OFFSETOPT_BUILD_ID, EIGEN_WORLD_VERSION,
                EIGEN_MAJOR_VERSION, EIGEN_MINOR_VERSION);
    return kExitOk;
  }
  Args args(argv + 2, argv + argc);
  try {
    if (!std::strcmp(command, "check")) return run_check(args);
    if (!std::strcmp(command, "inspect")) return run_inspect(args);
    if (!std::strcmp(command, "basis")) return run_basis(args);
    if (!std::strcmp(command, "skeleton")) return run_skeleton(args);
    if (!std::strcmp(command, "optimize")) return run_optimize(args);
    if (!std::strcmp(command, "generate")) return run_generate(args);
    if (!std::strcmp(command, "preview")) return run_preview(args);
    if (!std::strcmp(command, "batch")) return run_batch(args);
  } catch (const offsetopt::MeshInputError& e) {
    std::fprintf(stderr, "Error: %s\n", e.what());
    return kExitBadInput;
  } catch (const UsageError& e) {
    std::fprintf(stderr, "Error: %s\n", e.what());
    return kExitBadInput;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "Error: out of memory\n");
    return kExitInternal;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "Error: internal: %s\n", e.what());
    return kExitInternal;
  }
  std::fprintf(stderr, "Error: unknown command '%s' (try 'offsetopt --help')\n", command);
  return kExitBadInput;
}
