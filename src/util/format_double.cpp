#include "util/format_double.h"

#include <charconv>
#include <cmath>

namespace offsetopt {

void append_double(std::string& out, double value) {
  if (std::isnan(value)) { out += "nan"; return; }
  if (std::isinf(value)) { out += value > 0 ? "inf" : "-inf"; return; }
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

std::string format_double(double value) {
  std::string out;
  append_double(out, value);
  return out;
}

}  // namespace offsetopt
