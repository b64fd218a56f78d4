// Locale-independent, shortest round-trip text for a double (std::to_chars), so files written
// from the same numbers are byte-identical on every machine and read back to the same bits.
#pragma once
#include <string>

namespace offsetopt {

// Shortest text that parses back to exactly `value`; "nan", "inf", "-inf" for non-finite values
// (callers writing JSON must map those to null themselves).
std::string format_double(double value);

// Appends format_double(value) to `out` without a temporary string.
void append_double(std::string& out, double value);

}  // namespace offsetopt
