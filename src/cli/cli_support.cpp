#include "cli/cli_support.h"

#include "util/format_double.h"

#include <sys/stat.h>

#include <algorithm>
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

namespace offsetopt::cli {

namespace {

long long in_file(long long index, const std::vector<long long>& origin) {
  return origin.empty() || index < 0 ? index : origin[static_cast<std::size_t>(index)];
}

std::string lines_of(long long a, long long b, const std::vector<int>& line) {
  if (a < 0 || b < 0 || static_cast<std::size_t>(std::max(a, b)) >= line.size()) return {};
  return ", lines " + std::to_string(line[static_cast<std::size_t>(a)]) + " and " + std::to_string(line[static_cast<std::size_t>(b)]);
}

}  // namespace

std::string describe_self_intersections(const SelfIntersectionReport& report, const std::vector<long long>& face_origin,
                                        const std::vector<int>& face_line) {
  const long long f = in_file(report.first_face, face_origin), g = in_file(report.second_face, face_origin);
  return std::string(report.truncated ? "at least " : "") + std::to_string(report.pairs) +
         (report.pairs == 1 ? " self-intersecting face pair" : " self-intersecting face pairs") + " (first: faces " +
         std::to_string(f) + " and " + std::to_string(g) + lines_of(f, g, face_line) +
         "; faces numbered from 0 in file order after triangulation)";
}

std::string describe_pinches(const PinchReport& report, const std::vector<long long>& vertex_origin,
                             const std::vector<int>& vertex_line) {
  const long long a = in_file(report.first_vertex, vertex_origin), b = in_file(report.second_vertex, vertex_origin);
  return std::to_string(report.pairs) + (report.pairs == 1 ? " pinch" : " pinches") +
         ": distinct vertices at one position whose fans touch only there (first: vertices " + std::to_string(a) +
         " and " + std::to_string(b) + lines_of(a, b, vertex_line) + "; numbered from 0 in file order)";
}

LoadedMesh load_input(const std::string& path, const LoadOptions& options) {
  LoadedMesh loaded = load_mesh(path, options);
  const SelfIntersectionReport crossings = find_self_intersections(loaded.mesh);
  if (crossings.pairs > 0)
    loaded.warnings.push_back(describe_self_intersections(crossings, loaded.face_origin, loaded.face_line) +
                              "; accepted, but the mass properties count any overlap twice");
  if (crossings.work_cap_reached)
    loaded.warnings.push_back("self-intersection search stopped at its work cap (" + std::to_string(crossings.candidate_pairs) +
                              " candidate face pairs)");
  const PinchReport pinches = find_pinches(loaded.mesh);
  if (pinches.pairs > 0)
    loaded.warnings.push_back(describe_pinches(pinches, loaded.vertex_origin, loaded.vertex_line) + "; accepted");
  return loaded;
}

}  // namespace offsetopt::cli
