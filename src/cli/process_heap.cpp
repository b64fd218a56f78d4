#include "cli/process_heap.h"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <string>

#if defined(__GLIBC__)
#include <malloc.h>
#endif
#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace offsetopt::cli {

namespace {

#if defined(__GLIBC__) && defined(__linux__) && !defined(__SANITIZE_ADDRESS__)
constexpr std::size_t kHugePage = std::size_t(2) << 20;
// Address space only (pages come as they are touched), and under the trim threshold below, so
// that freeing never hands it back.
constexpr std::size_t kHugeHeap = std::size_t(512) << 20;

// The first line of a file of /proc or /sys, empty when it cannot be read.
std::string first_line(const char* path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}

// Huge pages on request only ("[madvise]", Debian's default; with "[always]" the heap has them
// already, with "[never]" not at all), and no strict overcommit, where the reserve would count
// in full against the commit limit.
bool huge_pages_on_request() {
  return first_line("/sys/kernel/mm/transparent_hugepage/enabled").find("[madvise]") != std::string::npos &&
         first_line("/proc/sys/vm/overcommit_memory") != "2";
}

// Grows the heap once by kHugeHeap (a block under the mmap threshold and larger than the heap's
// top, with that much top padding) and advises the range. Where the break cannot move, malloc maps
// the block instead and nothing is advised.
void advise_huge_heap() {
  const auto before = reinterpret_cast<std::uintptr_t>(sbrk(0));
  mallopt(M_TOP_PAD, static_cast<int>(kHugeHeap));
  void* volatile probe = std::malloc(8 << 20);  // volatile: a block only freed may be left out
  mallopt(M_TOP_PAD, 128 << 10);                // glibc's default
  const auto after = reinterpret_cast<std::uintptr_t>(sbrk(0));
  const std::uintptr_t start = (before + kHugePage - 1) & ~(kHugePage - 1);
  if (after > start + kHugePage) madvise(reinterpret_cast<void*>(start), (after - start) & ~(kHugePage - 1), MADV_HUGEPAGE);
  std::free(probe);
}
#endif

}  // namespace

// The pipeline frees and reallocates the same large work arrays many times (Lanczos panels, the
// per-evaluation Jacobians). glibc hands blocks above its adaptive mmap threshold back to the
// kernel at once, so each reuse pays fresh zeroed pages: on the 101,730-vertex bottle 530k page
// faults and about 1 s of system time, against 294k and 0.5-0.8 s with the blocks kept in the
// heap. A fault costs about 8 us on the 2-core machines we run on, and a demo goal took 12k-17k
// of them even so: the tasks and pools start about 30 threads a run, each of which took an arena
// of its own and touched fresh pages in it, and the heap came 4 KiB a fault. One arena and huge
// pages: about 1.1k faults.
void set_up_process_heap() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 32 << 20);  // glibc's largest allowed value
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  mallopt(M_ARENA_MAX, 1);
#if defined(__linux__) && !defined(__SANITIZE_ADDRESS__)
  if (huge_pages_on_request()) advise_huge_heap();
#endif
#endif
}

}  // namespace offsetopt::cli
