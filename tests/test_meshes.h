// Meshes the geometry, sparse and spectral tests run on. TODO(lead, when merging): add every
// demo mesh from mesh/demo_meshes.h to test_meshes() once it is on main; until then these
// primitives stand in.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "mesh/primitives.h"
#include "util/det_math.h"

namespace offsetopt::test {

struct NamedMesh {
  std::string name;
  Mesh mesh;
};

// A smooth, non-symmetric bump on an icosphere (no repeated eigenvalues).
inline Mesh bumpy_icosphere(int subdivisions) {
  Mesh m = make_icosphere(1.0, subdivisions);
  for (Eigen::Index i = 0; i < m.V.rows(); ++i) {
    const double x = m.V(i, 0), y = m.V(i, 1), z = m.V(i, 2);
    m.V.row(i) *= 1.0 + 0.3 * x * y + 0.2 * z * z * x + 0.1 * y;
  }
  return m;
}

// Small closed meshes (each under ~1,100 vertices), varied in shape, symmetry and triangle quality.
inline std::vector<NamedMesh> test_meshes() {
  std::vector<NamedMesh> meshes;
  meshes.push_back({"icosphere", make_icosphere(1.0, 3)});
  meshes.push_back({"bumpy icosphere", bumpy_icosphere(3)});
  meshes.push_back({"torus", make_torus(1.0, 0.3, 40, 16)});
  meshes.push_back({"capsule", make_capsule(0.5, 1.0, 32, 8, 12)});
  meshes.push_back({"cylinder", make_cylinder(0.7, -1.0, 1.5, 36, 10, 4)});
  meshes.push_back({"box", make_box({-1, -2, -0.5}, {1, 2, 0.5})});
  std::vector<std::pair<double, double>> vase;  // a vase-like profile, poles at both ends
  vase.push_back({0.0, 0.0});
  for (int r = 1; r < 24; ++r) {
    const double t = r / 24.0;
    vase.push_back({0.6 + 0.3 * det_sin(2.0 * kPi * t), 2.0 * t});
  }
  vase.push_back({0.0, 2.0});
  meshes.push_back({"revolution", make_revolution(vase, 30)});
  return meshes;
}

inline Mesh scaled(Mesh m, double factor) {
  m.V *= factor;
  return m;
}

}  // namespace offsetopt::test
