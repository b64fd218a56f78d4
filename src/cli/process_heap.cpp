#include "cli/process_heap.h"

#include <algorithm>
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

// The huge-page reserve: glibc on Linux, and not under a sanitizer, whose allocator is its own
// (GCC says so with __SANITIZE_ADDRESS__ and __SANITIZE_THREAD__, clang with __has_feature).
#if defined(__GLIBC__) && defined(__linux__) && !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)
#define OFFSETOPT_HUGE_HEAP 1
#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
#undef OFFSETOPT_HUGE_HEAP
#endif
#endif
#endif

namespace offsetopt::cli {

namespace {

#if defined(OFFSETOPT_HUGE_HEAP)
constexpr std::size_t kHugePage = std::size_t(2) << 20;
// Address space only: pages come as they are touched. Half the memory at most, so that the
// kernel's heuristic overcommit check never refuses it; 8 GiB covers a 10^6-vertex run (3.4 GB).
constexpr std::size_t kHugeHeapMax = std::size_t(8) << 30;
constexpr std::size_t kHugeHeapMin = std::size_t(128) << 20;

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

// Grows the heap once by a reserve (one block taken from the break, since nothing is mapped, and
// freed again; trimming is off) and advises the range; returns its bytes. Where the break cannot
// move that far (an address-space limit, ulimit -v), malloc maps the block instead or fails, and
// a quarter of the reserve is tried, down to kHugeHeapMin.
std::size_t advise_huge_heap() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page <= 0) return 0;
  std::size_t reserve = std::min(kHugeHeapMax, static_cast<std::size_t>(pages) * static_cast<std::size_t>(page) / 2);
  for (; reserve >= kHugeHeapMin; reserve /= 4) {
    const auto before = reinterpret_cast<std::uintptr_t>(sbrk(0));
    void* volatile probe = std::malloc(reserve);  // volatile: a block only freed may be left out
    const auto after = reinterpret_cast<std::uintptr_t>(sbrk(0));
    const std::uintptr_t start = (before + kHugePage - 1) & ~(kHugePage - 1);
    std::size_t advised = 0;
    if (after >= start + reserve / 2) {
      const std::size_t length = (after - start) & ~(kHugePage - 1);
      if (madvise(reinterpret_cast<void*>(start), length, MADV_HUGEPAGE) == 0) advised = length;
    }
    std::free(probe);
    if (advised > 0) return advised;
  }
  return 0;
}
#endif

}  // namespace

// The pipeline frees and reallocates the same large work arrays many times (Lanczos panels, the
// per-evaluation Jacobians, the contour's grids). Each block glibc maps by itself (those over its
// mmap threshold, at most 32 MiB) goes back to the kernel when freed, so each reuse pays fresh
// zeroed pages, and a page fault costs 8-12 us on the 2-core virtual machines we run on. So every
// block comes from one heap that is never trimmed, shared by every thread (the tasks and pools
// start about 30 threads a run, and each took an arena of its own and touched fresh pages in it),
// and that heap takes huge pages, one fault per 2 MiB. What it saves: docs/performance.md, "Page
// faults".
ProcessHeap set_up_process_heap() {
  ProcessHeap heap;
#if defined(__GLIBC__)
  const bool unmapped = mallopt(M_MMAP_MAX, 0) == 1;
  const bool untrimmed = mallopt(M_TRIM_THRESHOLD, -1) == 1;  // -1: never trim (mallopt(3))
  const bool one_arena = mallopt(M_ARENA_MAX, 1) == 1;
  heap.one_heap = unmapped && untrimmed && one_arena;
#if defined(OFFSETOPT_HUGE_HEAP)
  if (heap.one_heap && huge_pages_on_request()) heap.huge_reserve = advise_huge_heap();
#endif
#endif
  return heap;
}

}  // namespace offsetopt::cli
