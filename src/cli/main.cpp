// offsetopt: carve and thicken closed meshes with smooth offset surfaces so the printed object
// meets a mass-property goal (Musialski et al. 2015, "Reduced-Order Shape Optimization Using
// Offset Surfaces"). This file only dispatches to the subcommands.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <new>

#if defined(__GLIBC__)
#include <malloc.h>
#endif
#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

#include <Eigen/Core>

#include "cli/cli_support.h"
#include "cli/commands.h"
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

// The pipeline frees and reallocates the same large work arrays many times (Lanczos panels, the
// per-evaluation Jacobians). glibc hands blocks above its adaptive mmap threshold back to the
// kernel at once, so each reuse pays fresh zeroed pages: on the 101,730-vertex bottle 530k page
// faults and about 1 s of system time, against 294k and 0.5-0.8 s with the blocks kept in the
// heap. Results do not depend on any of this.
//
// A page fault costs about 8 us on the 2-core machines we run on (a demo goal takes 12k-17k of
// them: 0.1-0.15 s of system time), so the heap is also one arena for every thread (the tasks
// and pools start about 30 threads a run, each of which would take an arena of its own and touch
// fresh pages in it) and asks for transparent huge pages where the kernel gives them on request
// ("madvise", Debian's default): one fault per 2 MiB. Measured in docs/performance.md.
constexpr std::size_t kHugePage = std::size_t(2) << 20;
constexpr std::size_t kHugeHeap = std::size_t(512) << 20;  // address space: pages come on touch; under the trim threshold

void keep_large_blocks_in_heap() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 32 << 20);  // glibc's largest allowed value
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  mallopt(M_ARENA_MAX, 1);
#if defined(__linux__) && !defined(__SANITIZE_ADDRESS__)
  // Grow the heap once by kHugeHeap (a block under the mmap threshold, more than the top holds)
  // and advise that range. Where the break cannot move, malloc maps the block instead and
  // nothing is advised.
  const auto before = reinterpret_cast<std::uintptr_t>(sbrk(0));
  mallopt(M_TOP_PAD, static_cast<int>(kHugeHeap));
  // volatile: a block that is only freed could be left out by the compiler.
  void* volatile probe = std::malloc(8 << 20);
  mallopt(M_TOP_PAD, 128 << 10);  // glibc's default
  const auto after = reinterpret_cast<std::uintptr_t>(sbrk(0));
  const std::uintptr_t start = (before + kHugePage - 1) & ~(kHugePage - 1);
  if (after > start + kHugePage) madvise(reinterpret_cast<void*>(start), (after - start) & ~(kHugePage - 1), MADV_HUGEPAGE);
  std::free(probe);
#endif
#endif
}

}  // namespace

int main(int argc, char** argv) {
  using namespace offsetopt::cli;
  offsetopt::use_deterministic_eigen_blocking();
  keep_large_blocks_in_heap();
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
