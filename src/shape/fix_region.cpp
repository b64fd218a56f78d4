#include "shape/fix_region.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace offsetopt {

namespace {

bool parse_number(const std::string& text, double& value) {
  if (text.empty()) return false;
  char* end = nullptr;
  errno = 0;
  value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && errno != ERANGE && std::isfinite(value);
}

}  // namespace

std::string parse_fix_region(const std::string& text, FixRegion& region) {
  region = FixRegion();
  region.text = text;
  if (text.rfind("sphere:", 0) == 0) {
    double values[4];
    std::size_t start = 7;
    for (int i = 0; i < 4; ++i) {
      const std::size_t comma = text.find(',', start);
      const bool last = i == 3;
      if (last != (comma == std::string::npos)) return "sphere region needs exactly four numbers: sphere:X,Y,Z,R";
      const std::string part = text.substr(start, last ? std::string::npos : comma - start);
      if (!parse_number(part, values[i])) return "'" + part + "' is not a finite number";
      start = comma + 1;
    }
    if (!(values[3] > 0.0)) return "sphere radius must be > 0";
    region.kind = FixRegion::Kind::sphere;
    for (int i = 0; i < 3; ++i) region.center[i] = values[i];
    region.radius = values[3];
    return {};
  }
  if (text.size() >= 3 && (text[0] == 'x' || text[0] == 'y' || text[0] == 'z') && (text[1] == '>' || text[1] == '<')) {
    if (!parse_number(text.substr(2), region.value)) return "'" + text.substr(2) + "' is not a finite number";
    region.kind = FixRegion::Kind::half_space;
    region.axis = text[0] - 'x';
    region.above = text[1] == '>';
    return {};
  }
  return "unknown region '" + text + "' (expected x>V, z<V, ... or sphere:X,Y,Z,R)";
}

std::vector<char> fixed_vertices(const Mesh& mesh, const FixRegion& region) {
  std::vector<char> fixed(static_cast<std::size_t>(mesh.V.rows()), 0);
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    bool inside = false;
    if (region.kind == FixRegion::Kind::half_space) {
      const double c = mesh.V(i, region.axis);
      inside = region.above ? c > region.value : c < region.value;
    } else if (region.kind == FixRegion::Kind::sphere) {
      const double dx = mesh.V(i, 0) - region.center[0], dy = mesh.V(i, 1) - region.center[1],
                   dz = mesh.V(i, 2) - region.center[2];
      inside = dx * dx + dy * dy + dz * dz <= region.radius * region.radius;
    }
    fixed[static_cast<std::size_t>(i)] = inside ? 1 : 0;
  }
  return fixed;
}

}  // namespace offsetopt
