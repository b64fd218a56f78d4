// Raw DEFLATE decompression (RFC 1951): stored, fixed-Huffman and dynamic-Huffman blocks, as zip
// entries written by slicers (PrusaSlicer, Bambu Studio, Cura) use them. Written for hostile
// input: every length, distance and code table is checked before use, the output never grows
// beyond `max_output` bytes, and reading past the input is an error, never undefined behaviour.
#pragma once
#include <cstddef>
#include <string>
#include <string_view>

namespace offsetopt {

enum class InflateStatus { ok, truncated, bad_data, too_large };

struct InflateResult {
  InflateStatus status = InflateStatus::ok;
  std::string message;        // what is wrong, when status != ok
  std::size_t input_used = 0;  // bytes of `compressed` consumed (up to the end of the last block)
};

// Decompresses `compressed` into `out` (replaced). Stops with too_large as soon as the output
// would exceed `max_output`.
InflateResult inflate(std::string_view compressed, std::size_t max_output, std::string& out);

}  // namespace offsetopt
