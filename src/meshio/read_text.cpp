#include "meshio/read_text.h"

#include <charconv>
#include <cstring>
#include <limits>

#include "meshio/load_mesh.h"

namespace offsetopt {

bool LineScanner::next(std::string_view& line) {
  if (position_ >= text_.size()) return false;
  const std::size_t start = position_;
  std::size_t end = start;
  while (end < text_.size() && text_[end] != '\n' && text_[end] != '\r') ++end;
  line = text_.substr(start, end - start);
  position_ = end;
  if (position_ < text_.size()) {
    if (text_[position_] == '\r' && position_ + 1 < text_.size() && text_[position_ + 1] == '\n') ++position_;
    ++position_;
  }
  ++line_number_;
  return true;
}

void split_tokens(std::string_view line, std::vector<std::string_view>& tokens, bool all_whitespace) {
  tokens.clear();
  auto is_space = [all_whitespace](char c) {
    return c == ' ' || c == '\t' || (all_whitespace && (c == '\v' || c == '\f'));
  };
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
}

namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }

// For a token from_chars rejected as out of range: does it overflow (true) or underflow?
// Decided by the decimal exponent of the leading digit, which is all that matters at 1e+-308.
bool overflows(std::string_view token) {
  std::size_t i = 0;
  if (i < token.size() && (token[i] == '-' || token[i] == '+')) ++i;
  long long leading = 0;  // position of the first non-zero digit relative to the decimal point
  bool seen_point = false, seen_nonzero = false;
  long long integer_digits = 0, leading_zero_fraction = 0;
  for (; i < token.size() && (is_digit(token[i]) || token[i] == '.'); ++i) {
    if (token[i] == '.') { seen_point = true; continue; }
    if (!seen_nonzero && token[i] == '0') {
      if (seen_point) ++leading_zero_fraction;
      continue;
    }
    seen_nonzero = true;
    if (!seen_point) ++integer_digits;
  }
  leading = integer_digits > 0 ? integer_digits - 1 : -(leading_zero_fraction + 1);
  long long exponent = 0;
  if (i < token.size() && (token[i] == 'e' || token[i] == 'E')) {
    ++i;
    bool negative = false;
    if (i < token.size() && (token[i] == '-' || token[i] == '+')) negative = token[i++] == '-';
    for (; i < token.size() && is_digit(token[i]); ++i)
      if (exponent < 100000) exponent = exponent * 10 + (token[i] - '0');
    if (negative) exponent = -exponent;
  }
  return leading + exponent > 0;
}

}  // namespace

bool parse_real(std::string_view token, double& value) {
  if (token.empty()) return false;
  std::string_view body = token;
  // from_chars takes no leading '+'; strtod (and so every exporter) may write one.
  if (body[0] == '+') {
    body.remove_prefix(1);
    if (body.empty() || body[0] == '-' || body[0] == '+') return false;
  }
  double parsed = 0.0;
  const auto result = std::from_chars(body.data(), body.data() + body.size(), parsed, std::chars_format::general);
  if (result.ptr != body.data() + body.size()) return false;
  if (result.ec == std::errc::result_out_of_range) {
    const bool negative = body[0] == '-';
    const double magnitude = overflows(body) ? std::numeric_limits<double>::infinity() : 0.0;
    value = negative ? -magnitude : magnitude;
    return true;
  }
  if (result.ec != std::errc()) return false;
  value = parsed;
  return true;
}

bool parse_integer(std::string_view token, std::int64_t& value, bool& overflow) {
  overflow = false;
  if (token.empty()) return false;
  std::string_view body = token;
  if (body[0] == '+') body.remove_prefix(1);
  if (body.empty()) return false;
  const std::size_t digits_start = body[0] == '-' ? 1 : 0;
  if (digits_start >= body.size()) return false;
  for (std::size_t i = digits_start; i < body.size(); ++i)
    if (!is_digit(body[i])) return false;
  std::int64_t parsed = 0;
  const auto result = std::from_chars(body.data(), body.data() + body.size(), parsed);
  if (result.ec == std::errc::result_out_of_range) {
    overflow = true;
    value = body[0] == '-' ? std::numeric_limits<std::int64_t>::min() : std::numeric_limits<std::int64_t>::max();
    return true;
  }
  if (result.ec != std::errc() || result.ptr != body.data() + body.size()) return false;
  value = parsed;
  return true;
}

bool next_token(std::string_view text, std::size_t& position, int& line, std::string_view& token) {
  while (position < text.size()) {
    const char c = text[position];
    if (c == '\n') {
      ++line;
    } else if (c == '\r') {
      if (!(position + 1 < text.size() && text[position + 1] == '\n')) ++line;
    } else if (c != ' ' && c != '\t' && c != '\v' && c != '\f') {
      break;
    }
    ++position;
  }
  if (position >= text.size()) return false;
  const std::size_t start = position;
  while (position < text.size() && !std::strchr(" \t\v\f\r\n", text[position])) ++position;
  token = text.substr(start, position - start);
  return true;
}

int line_of_offset(std::string_view text, std::size_t offset) {
  int line = 1;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') ++line;
    else if (text[i] == '\r' && !(i + 1 < text.size() && text[i + 1] == '\n')) ++line;
  }
  return line;
}

void refuse_nul_bytes(const std::string& name, std::string_view text) {
  const void* nul = std::memchr(text.data(), '\0', text.size());
  if (!nul) return;
  const std::size_t offset = static_cast<std::size_t>(static_cast<const char*>(nul) - text.data());
  throw MeshInputError(name + ":" + std::to_string(line_of_offset(text, offset)) +
                       ": binary data (byte 0x00) in a text file");
}

bool equals_ignoring_case(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    char x = a[i], y = b[i];
    if (x >= 'A' && x <= 'Z') x = static_cast<char>(x - 'A' + 'a');
    if (y >= 'A' && y <= 'Z') y = static_cast<char>(y - 'A' + 'a');
    if (x != y) return false;
  }
  return true;
}

}  // namespace offsetopt
