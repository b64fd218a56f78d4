// libFuzzer harness: read_3mf on arbitrary bytes (zip container, inflate, XML scanner, build and
// components; assertions in fuzz_support.h). A 3MF package may legitimately inflate to about
// 1032 times its size (DEFLATE's largest ratio), so the heap budget counts the bytes the
// package's entries can inflate to, as the central directory declares them and capped by that
// ratio, at the same 256 bytes per byte as the other readers.
#include <algorithm>

#include "fuzz/fuzz_support.h"
#include "mesh/read_3mf.h"
#include "mesh/zip_archive.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  std::vector<offsetopt::ZipEntryInfo> entries;
  std::string error;
  std::uint64_t inflatable = 0;
  if (offsetopt::list_zip(bytes, entries, error))
    for (const auto& e : entries) inflatable += std::min<std::uint64_t>(e.size, 1032 * e.compressed_size + 1024);
  entries.clear();
  entries.shrink_to_fit();
  const std::size_t budget = offsetopt::fuzz::kBytesPerInputByte * (size + static_cast<std::size_t>(inflatable)) +
                             offsetopt::fuzz::kFixedBytes;
  return offsetopt::fuzz::fuzz_one_reader("fuzz.3mf", data, size, offsetopt::read_3mf, budget);
}
