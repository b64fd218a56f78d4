// Checks on a mesh's connectivity shared by the tests of written surfaces (contoured cavities,
// marching tetrahedra): written here independently of the code under test.
#pragma once
#include <map>
#include <utility>

#include "mesh/mesh.h"

namespace offsetopt::test {

// Each directed edge used exactly once and its opposite exactly once: every shell closed,
// consistently oriented and edge-manifold.
inline bool closed_and_oriented(const Mesh& mesh) {
  std::map<std::pair<int, int>, int> directed;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) ++directed[{mesh.F(f, c), mesh.F(f, (c + 1) % 3)}];
  for (const auto& [edge, count] : directed) {
    if (count != 1) return false;
    const auto opposite = directed.find({edge.second, edge.first});
    if (opposite == directed.end() || opposite->second != 1) return false;
  }
  return true;
}

// a and b as one mesh (b's vertices after a's): the shells of a solid with a cavity, or two parts.
inline Mesh join(const Mesh& a, const Mesh& b) {
  Mesh m;
  m.V.resize(a.V.rows() + b.V.rows(), 3);
  m.V << a.V, b.V;
  m.F.resize(a.F.rows() + b.F.rows(), 3);
  m.F << a.F, (b.F.array() + static_cast<int>(a.V.rows())).matrix();
  return m;
}

}  // namespace offsetopt::test
