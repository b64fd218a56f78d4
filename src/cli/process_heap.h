// How this process's heap is set up, once, at the start of main, before any thread starts.
// Results never depend on it: only how many page faults the run takes (docs/performance.md,
// "Page faults").
#pragma once

namespace offsetopt::cli {

// Keeps freed blocks in the heap (glibc), uses one arena for every thread, and asks the kernel
// for transparent huge pages over the heap where it gives them only on request. Does nothing
// where these do not apply (another C library, a sanitizer's allocator, strict overcommit).
void set_up_process_heap();

}  // namespace offsetopt::cli
