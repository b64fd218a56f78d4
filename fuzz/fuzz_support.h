// Shared pieces of the libFuzzer harnesses (fuzz/README.md): what every harness asserts beyond
// "no crash", so that a finding is anything the unattended binary must never do.
//
//  - Only MeshInputError may leave a reader or load_raw_mesh. Any other exception (out_of_range,
//    invalid_argument, bad_alloc, ...) escapes the harness and libFuzzer reports it as a crash.
//  - An error message is one line of printable ASCII of bounded length that starts with the file
//    name: hostile bytes must come out quoted (quote_bytes), never flood a terminal.
//  - A RawMesh respects the caps of meshio/read_raw_mesh.h and its per-element line tables.
//  - Memory is proportional to the input: the peak of live heap bytes while one input is
//    processed stays below kBytesPerInputByte * size + kFixedBytes. Measured with the sanitizer
//    allocator's hooks (every malloc and operator new of the process goes through them), so this
//    needs the ASan build that fuzz/CMakeLists.txt requires.
//  - Time: libFuzzer's -timeout (10 s in scripts/fuzz.sh) turns a hang into a finding.
// A violated assertion prints what broke and aborts, which libFuzzer saves as a crash input.
#pragma once
#include <sanitizer/allocator_interface.h>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "io/zip_archive.h"
#include "meshio/load_mesh.h"
#include "meshio/read_raw_mesh.h"

namespace offsetopt::fuzz {

// Budget for the peak of live heap bytes per input. The largest legitimate ratio comes from
// polygons in binary PLY: a 255-corner face costs 256 input bytes with uchar indices and becomes
// 253 triangles (corners, Eigen copies, the validator's half-edges, sort buffers and component
// lists): 126 bytes of peak heap per input byte through fuzz_load_inspect (fuzz/make_hostile.py,
// ply_binary_fans.ply). Text meshes need 7 to 12 per byte, and the fixed part stays below
// 200 KB on the whole corpus (OFFSETOPT_FUZZ_HEAP=1 prints every peak).
constexpr std::size_t kBytesPerInputByte = 256;
constexpr std::size_t kFixedBytes = std::size_t{1} << 20;

[[noreturn]] inline void fail(const char* what, const std::string& detail) {
  std::fprintf(stderr, "fuzz assertion failed: %s\n  %s\n", what, detail.c_str());
  std::fflush(stderr);
  std::abort();
}

#define OFFSETOPT_FUZZ_CHECK(condition, detail) \
  do {                                          \
    if (!(condition)) ::offsetopt::fuzz::fail(#condition, (detail)); \
  } while (0)

// Peak live heap bytes between arm() and disarm(), from the sanitizer allocator's hooks.
class HeapWatch {
 public:
  static void install() {
    static const bool installed = [] {
      __sanitizer_install_malloc_and_free_hooks(&on_malloc, &on_free);
      return true;
    }();
    (void)installed;
  }
  static void arm() {
    live().store(0, std::memory_order_relaxed);
    peak().store(0, std::memory_order_relaxed);
    armed().store(true, std::memory_order_relaxed);
  }
  // Returns the peak since arm().
  static std::int64_t disarm() {
    armed().store(false, std::memory_order_relaxed);
    return peak().load(std::memory_order_relaxed);
  }

 private:
  static std::atomic<std::int64_t>& live() {
    static std::atomic<std::int64_t> value{0};
    return value;
  }
  static std::atomic<std::int64_t>& peak() {
    static std::atomic<std::int64_t> value{0};
    return value;
  }
  static std::atomic<bool>& armed() {
    static std::atomic<bool> value{false};
    return value;
  }
  static void on_malloc(const volatile void*, std::size_t size) {
    if (!armed().load(std::memory_order_relaxed)) return;
    const std::int64_t now = live().fetch_add(static_cast<std::int64_t>(size), std::memory_order_relaxed) +
                             static_cast<std::int64_t>(size);
    std::int64_t seen = peak().load(std::memory_order_relaxed);
    while (now > seen && !peak().compare_exchange_weak(seen, now, std::memory_order_relaxed)) {
    }
  }
  static void on_free(const volatile void* pointer) {
    if (!pointer || !armed().load(std::memory_order_relaxed)) return;
    // Blocks allocated before arm() make `live` dip below zero; the peak is still an upper bound
    // of what this input added.
    live().fetch_sub(static_cast<std::int64_t>(__sanitizer_get_allocated_size(const_cast<const void*>(pointer))),
                     std::memory_order_relaxed);
  }
};

// Arms HeapWatch for one input and checks the budget when it goes out of scope (also when an
// exception passes through, so a refusal that allocated too much is caught as well).
class HeapBudget {
 public:
  explicit HeapBudget(std::size_t input_size, std::size_t budget = 0)
      : input_size_(input_size), budget_(budget ? budget : kBytesPerInputByte * input_size + kFixedBytes) {
    HeapWatch::install();
    HeapWatch::arm();
  }
  ~HeapBudget() {
    const std::int64_t peak = HeapWatch::disarm();
    const std::int64_t budget = static_cast<std::int64_t>(budget_);
    // OFFSETOPT_FUZZ_HEAP=1: print the peak of every input (to size the budget).
    static const bool report = std::getenv("OFFSETOPT_FUZZ_HEAP") != nullptr;
    if (report) {
      std::fprintf(stderr, "heap peak %lld bytes for %zu input bytes (%.1f per byte)\n", static_cast<long long>(peak),
                   input_size_, input_size_ ? static_cast<double>(peak) / static_cast<double>(input_size_) : 0.0);
    }
    if (peak > budget) {
      fail("peak heap <= budget", "input of " + std::to_string(input_size_) + " bytes reached a peak of " +
                                      std::to_string(peak) + " live heap bytes; the budget is " +
                                      std::to_string(budget));
    }
  }
  HeapBudget(const HeapBudget&) = delete;
  HeapBudget& operator=(const HeapBudget&) = delete;

 private:
  std::size_t input_size_;
  std::size_t budget_;
};

// For a zip (3MF) input: the bytes its entries can inflate to, as its central directory declares
// them and capped at DEFLATE's largest ratio (1032:1); 0 for anything else. Budgets count these
// bytes like input bytes, since a 3MF package legitimately holds its model compressed.
inline std::size_t inflatable_bytes(const std::uint8_t* data, std::size_t size) {
  std::vector<ZipEntryInfo> entries;
  std::string error;
  std::uint64_t total = 0;
  if (list_zip(std::string_view(reinterpret_cast<const char*>(data), size), entries, error))
    for (const ZipEntryInfo& e : entries) total += e.size < 1032 * e.compressed_size + 1024 ? e.size : 1032 * e.compressed_size + 1024;
  return static_cast<std::size_t>(total);
}

// One line of printable ASCII, starting with `name`, at most 1024 characters.
inline void check_error_message(const std::string& name, const char* what) {
  const std::string message = what;
  OFFSETOPT_FUZZ_CHECK(message.rfind(name, 0) == 0, "message does not start with the file name: " + message);
  OFFSETOPT_FUZZ_CHECK(message.size() <= 1024, "message of " + std::to_string(message.size()) + " characters");
  for (const char c : message) {
    const unsigned char u = static_cast<unsigned char>(c);
    OFFSETOPT_FUZZ_CHECK(u >= 0x20 && u < 0x7f, "unprintable byte " + std::to_string(u) + " in message");
  }
}

inline void check_raw_mesh(const RawMesh& raw, bool text_format) {
  OFFSETOPT_FUZZ_CHECK(raw.V.cols() == 3 && raw.F.cols() == 3, "V and F must have 3 columns");
  OFFSETOPT_FUZZ_CHECK(raw.V.rows() <= kMaxVertices, std::to_string(raw.V.rows()) + " vertices");
  OFFSETOPT_FUZZ_CHECK(raw.F.rows() <= kMaxFaces, std::to_string(raw.F.rows()) + " faces");
  if (text_format) {
    OFFSETOPT_FUZZ_CHECK(raw.vertex_line.size() == static_cast<std::size_t>(raw.V.rows()), "vertex_line size");
    OFFSETOPT_FUZZ_CHECK(raw.face_line.size() == static_cast<std::size_t>(raw.F.rows()), "face_line size");
    for (const int line : raw.vertex_line) OFFSETOPT_FUZZ_CHECK(line >= 1, "vertex line " + std::to_string(line));
    for (const int line : raw.face_line) OFFSETOPT_FUZZ_CHECK(line >= 1, "face line " + std::to_string(line));
  } else {
    OFFSETOPT_FUZZ_CHECK(raw.vertex_line.empty() && raw.face_line.empty(), "binary formats carry no line numbers");
  }
  for (const std::string& warning : raw.warnings) {
    OFFSETOPT_FUZZ_CHECK(warning.size() <= 1024, "warning of " + std::to_string(warning.size()) + " characters");
    for (const char c : warning) {
      const unsigned char u = static_cast<unsigned char>(c);
      OFFSETOPT_FUZZ_CHECK(u >= 0x20 && u < 0x7f, "unprintable byte " + std::to_string(u) + " in warning: " + warning);
    }
  }
}

inline bool is_text_format(MeshFormat format) {
  return format == MeshFormat::obj || format == MeshFormat::stl_ascii || format == MeshFormat::off ||
         format == MeshFormat::ply_ascii;
}

// The body of the four reader harnesses: `read(name, bytes)` either returns a RawMesh that passes
// check_raw_mesh or throws MeshInputError with a clean message; memory stays within the budget.
// `budget_bytes` replaces the default budget (0: kBytesPerInputByte * size + kFixedBytes).
template <typename Reader>
int fuzz_one_reader(const char* name, const std::uint8_t* data, std::size_t size, Reader read,
                    std::size_t budget_bytes = 0) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  HeapBudget budget(size, budget_bytes);
  try {
    const RawMesh raw = read(name, bytes);
    check_raw_mesh(raw, is_text_format(raw.format));
  } catch (const MeshInputError& e) {
    check_error_message(name, e.what());
  }
  return 0;
}

}  // namespace offsetopt::fuzz
