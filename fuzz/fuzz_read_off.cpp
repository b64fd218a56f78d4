// libFuzzer harness: read_off on arbitrary bytes (assertions in fuzz_support.h).
#include "fuzz/fuzz_support.h"
#include "meshio/read_off.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return offsetopt::fuzz::fuzz_one_reader("fuzz.off", data, size, offsetopt::read_off);
}
