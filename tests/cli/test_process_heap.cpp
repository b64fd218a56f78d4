// The heap's set-up (cli/process_heap.h), read back from the kernel's own account of this
// process's mappings (/proc/self/smaps): a large block allocated afterwards lies in the heap (the
// program break's mapping, not one mapped for it alone) and, wherever /sys and /proc say that huge
// pages come on request and overcommit is not strict (read here, not taken from the set-up's own
// answer), in a range advised for huge pages (VmFlags "hg"). A reserve never made (the first
// version's probe block, only freed, was left out by the compiler) or trimmed back by the free
// (its second version) leaves the block's range unadvised, and fails it; both were checked.
#include <doctest/doctest.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "../support.h"
#include "cli/process_heap.h"

namespace {

struct Mapping {
  bool found = false;
  std::string name;   // "[heap]", a file, or empty for an anonymous mapping
  std::string flags;  // the VmFlags line's two-letter flags
};

// The mapping of /proc/self/smaps that holds `address`.
Mapping mapping_of(const void* address) {
  const auto at = reinterpret_cast<std::uintptr_t>(address);
  std::ifstream smaps("/proc/self/smaps");
  Mapping m;
  bool inside = false;
  std::string line;
  while (std::getline(smaps, line)) {
    std::istringstream words(line);
    std::string first;
    words >> first;
    const std::size_t dash = first.find('-');
    if (dash != std::string::npos && first.find(':') == std::string::npos) {  // a mapping's header
      if (inside) return m;
      const std::uintptr_t lo = std::stoull(first.substr(0, dash), nullptr, 16);
      const std::uintptr_t hi = std::stoull(first.substr(dash + 1), nullptr, 16);
      inside = lo <= at && at < hi;
      if (inside) {
        m.found = true;
        std::string permissions, offset, device, inode;
        words >> permissions >> offset >> device >> inode;
        std::getline(words >> std::ws, m.name);
      }
    } else if (inside && first == "VmFlags:") {
      std::getline(words >> std::ws, m.flags);
    }
  }
  return m;
}

}  // namespace

TEST_CASE("process heap: a large block after the set-up lies in the heap, in a range advised for huge pages") {
  const offsetopt::cli::ProcessHeap heap = offsetopt::cli::set_up_process_heap();
  if (!heap.one_heap) {
    offsetopt::test::skip_test("not glibc's allocator here (a sanitizer's, or another C library)");
    return;
  }
  const std::size_t size = std::size_t(64) << 20;  // over glibc's largest mmap threshold (32 MiB)
  char* block = static_cast<char*>(std::malloc(size));
  REQUIRE(block != nullptr);
  std::memset(block, 1, size);
  const Mapping m = mapping_of(block + size / 2);
  std::free(block);
  REQUIRE(m.found);
  CHECK(m.name == "[heap]");  // from the break: M_MMAP_MAX 0 maps no block by itself
  using offsetopt::test::read_file;
  const bool on_request = read_file("/sys/kernel/mm/transparent_hugepage/enabled").find("[madvise]") != std::string::npos &&
                          read_file("/proc/sys/vm/overcommit_memory").rfind('2', 0) != 0;
  if (!on_request) {
    CHECK(heap.huge_reserve == 0);
    offsetopt::test::skip_test("the kernel gives huge pages always or never here, or overcommit is strict: no reserve");
    return;
  }
  CHECK(heap.huge_reserve >= size);
  CHECK((" " + m.flags + " ").find(" hg ") != std::string::npos);
}
