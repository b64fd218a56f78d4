// Strict, locale-independent pieces shared by the text-format readers (OBJ, ASCII STL, OFF,
// ASCII PLY): line splitting with line numbers, whitespace tokens and whole-token number parsing
// (the quoting of untrusted bytes for error messages is util/quote_bytes.h, included here).
#pragma once
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "util/quote_bytes.h"

namespace offsetopt {

// Splits text into lines the way tinyobjloader does: "\n", "\r\n" or a lone "\r" ends a line,
// so line numbers agree with it. The terminator is not part of the returned line.
class LineScanner {
 public:
  explicit LineScanner(std::string_view text) : text_(text) {}
  // The next line, or false at the end of the text.
  bool next(std::string_view& line);
  // 1-based number of the line last returned by next().
  int line_number() const { return line_number_; }
  // Byte offset just past the terminator of the line last returned.
  std::size_t offset() const { return position_; }

 private:
  std::string_view text_;
  std::size_t position_ = 0;
  int line_number_ = 0;
};

// Splits a line at spaces, tabs and (when `all_whitespace`) \v and \f.
void split_tokens(std::string_view line, std::vector<std::string_view>& tokens, bool all_whitespace = false);

// The whole token must be a decimal real number: optional sign, digits, fraction, exponent, or
// nan/inf/infinity (any case). Correctly rounded (std::from_chars), never locale-dependent.
// Magnitudes beyond the double range become +-infinity, below it +-0. False if not a number.
bool parse_real(std::string_view token, double& value);

// The whole token must be a decimal integer with optional sign. `overflow` is set (and the
// function returns true) when it is well-formed but does not fit in 64 bits.
bool parse_integer(std::string_view token, std::int64_t& value, bool& overflow);

// The next token of `text` at or after `position` (tokens end at spaces, tabs, \v, \f, line ends
// and NUL), moving `position` past it and counting in `line` the line ends skipped (as
// LineScanner does); false at the end of the text.
bool next_token(std::string_view text, std::size_t& position, int& line, std::string_view& token);

// Line number (1-based) of byte `offset` in `text`, counting line ends like LineScanner.
int line_of_offset(std::string_view text, std::size_t offset);

// Throws MeshInputError "<name>:<line>: binary data (byte 0x00) in a text file" if the text holds
// a NUL byte; text formats never contain one and parsers would stop there silently.
void refuse_nul_bytes(const std::string& name, std::string_view text);

// Case-insensitive ASCII comparison.
bool equals_ignoring_case(std::string_view a, std::string_view b);

}  // namespace offsetopt
