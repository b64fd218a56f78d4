#include "cli/cli_support.h"

#include "util/format_double.h"

#include <sys/stat.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>

namespace offsetopt::cli {

const std::string& ArgCursor::value_of(const std::string& name) {
  if (done()) throw UsageError("option " + name + " needs a value");
  return next();
}

double parse_double(const std::string& text, const std::string& option, double lo, double hi) {
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(value))
    throw UsageError(option + " expects a number, got '" + text + "'");
  if (value < lo || value > hi)
    throw UsageError(option + " must be in [" + format_double(lo) + ", " + format_double(hi) + "], got " + text);
  return value;
}

int parse_int(const std::string& text, const std::string& option, int lo, int hi) {
  char* end = nullptr;
  errno = 0;
  const long value = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE)
    throw UsageError(option + " expects an integer, got '" + text + "'");
  if (value < lo || value > hi)
    throw UsageError(option + " must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + text);
  return static_cast<int>(value);
}

namespace {

bool same_file(const std::string& a, const std::string& b) {
  struct stat sa {}, sb {};
  if (::stat(a.c_str(), &sa) != 0 || ::stat(b.c_str(), &sb) != 0) return a == b;
  return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

}  // namespace

void refuse_overwriting_input(const std::string& output, const std::vector<std::string>& inputs) {
  for (const auto& input : inputs)
    if (output != "-" && same_file(output, input))
      throw UsageError("output " + output + " is the input file; refusing to overwrite it");
}

void write_text(const std::string& path, const std::string& text, const std::vector<std::string>& inputs) {
  if (path == "-") {
    std::fwrite(text.data(), 1, text.size(), stdout);
    std::fflush(stdout);
    return;
  }
  refuse_overwriting_input(path, inputs);
  std::ofstream out(path, std::ios::binary);
  if (!out) throw UsageError("cannot open " + path + " for writing");
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (!out) throw UsageError("writing " + path + " failed");
}

void print_warnings(const std::vector<std::string>& warnings, bool quiet) {
  if (quiet) return;
  for (const auto& w : warnings) std::fprintf(stderr, "Warning: %s\n", w.c_str());
}

}  // namespace offsetopt::cli
