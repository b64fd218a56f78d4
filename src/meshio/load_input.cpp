#include "meshio/load_input.h"

#include <algorithm>

namespace offsetopt {

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

InputMesh load_input(const std::string& path, const LoadOptions& options) {
  InputMesh loaded;
  static_cast<LoadedMesh&>(loaded) = load_mesh(path, options);
  loaded.self_intersections = find_self_intersections(loaded.mesh, 1000000, options.threads);
  const SelfIntersectionReport& crossings = loaded.self_intersections;
  if (crossings.pairs > 0)
    loaded.warnings.push_back(describe_self_intersections(crossings, loaded.face_origin, loaded.face_line) +
                              "; accepted, but the mass properties count any overlap twice");
  if (crossings.work_cap_reached)
    loaded.warnings.push_back("self-intersection search stopped at its work cap (" + std::to_string(crossings.candidate_pairs) +
                              " candidate face pairs)");
  loaded.pinches = find_pinches(loaded.mesh);
  const PinchReport& pinches = loaded.pinches;
  if (pinches.pairs > 0)
    loaded.warnings.push_back(describe_pinches(pinches, loaded.vertex_origin, loaded.vertex_line) + "; accepted");
  return loaded;
}

}  // namespace offsetopt
