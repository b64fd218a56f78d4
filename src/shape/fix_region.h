// Fixed regions (`--fix`, paper 4.2 "geometric bounds" and 5.2): vertices whose inner and outer
// offsets are held at 0, so the two surfaces coincide there and the printed solid opens.
// Region syntax (input units):
//   AXIS>VALUE or AXIS<VALUE   AXIS one of x, y, z: a half-space, e.g. "z>230" (the top)
//   sphere:X,Y,Z,R             the vertices within distance R of (X, Y, Z)
#pragma once
#include <string>
#include <vector>

#include "mesh/mesh.h"

namespace offsetopt {

struct FixRegion {
  enum class Kind { none, half_space, sphere };
  Kind kind = Kind::none;
  int axis = 2;           // half_space: 0, 1, 2 for x, y, z
  bool above = true;      // half_space: coordinate > value (else <)
  double value = 0.0;
  double center[3] = {0.0, 0.0, 0.0};  // sphere
  double radius = 0.0;
  std::string text;       // as given
};

// Parses the syntax above; returns an empty string on success, else what is wrong.
std::string parse_fix_region(const std::string& text, FixRegion& region);

// One flag per vertex: nonzero inside the region (all zero for Kind::none).
std::vector<char> fixed_vertices(const Mesh& mesh, const FixRegion& region);

}  // namespace offsetopt
