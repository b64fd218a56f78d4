// libFuzzer harness: read_ply on arbitrary bytes (assertions in fuzz_support.h).
#include "fuzz/fuzz_support.h"
#include "meshio/read_ply.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return offsetopt::fuzz::fuzz_one_reader("fuzz.ply", data, size, offsetopt::read_ply);
}
