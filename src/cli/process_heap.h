// How this process's heap is set up, once, at the start of main, before any thread starts.
// Results never depend on it: only how many page faults the run takes (docs/performance.md,
// "Page faults").
#pragma once
#include <cstddef>

namespace offsetopt::cli {

struct ProcessHeap {
  bool one_heap = false;        // glibc: every block from one arena's heap, never unmapped or trimmed
  std::size_t huge_reserve = 0;  // bytes of heap advised for huge pages (0: none)
};

// Keeps every block in one heap that is never trimmed (glibc), shared by every thread, and asks
// the kernel for transparent huge pages over a reserve of that heap where it gives them only on
// request. Does what applies: nothing under another C library, no reserve under a sanitizer's
// allocator, with huge pages always or never, or with strict overcommit.
ProcessHeap set_up_process_heap();

}  // namespace offsetopt::cli
