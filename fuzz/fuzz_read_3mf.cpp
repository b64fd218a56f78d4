// libFuzzer harness: read_3mf on arbitrary bytes (zip container, inflate, XML scanner, build and
// components; assertions in fuzz_support.h). A 3MF package may legitimately inflate to about
// 1032 times its size (DEFLATE's largest ratio), so the heap budget also counts the bytes the
// package's entries can inflate to (inflatable_bytes), at the same 256 bytes per byte as the
// other readers.
#include "fuzz/fuzz_support.h"
#include "meshio/read_3mf.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::size_t budget = offsetopt::fuzz::kBytesPerInputByte * (size + offsetopt::fuzz::inflatable_bytes(data, size)) +
                             offsetopt::fuzz::kFixedBytes;
  return offsetopt::fuzz::fuzz_one_reader("fuzz.3mf", data, size, offsetopt::read_3mf, budget);
}
