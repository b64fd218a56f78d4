#include "geometry/mesh_shells.h"

#include <algorithm>
#include <numeric>

#include <Eigen/Geometry>

namespace offsetopt {

MeshShells mesh_shells(const Mesh& mesh, const Eigen::Vector3d& origin) {
  std::vector<int> parent(static_cast<std::size_t>(mesh.V.rows()));
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int v) {
    while (parent[static_cast<std::size_t>(v)] != v) {
      parent[static_cast<std::size_t>(v)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(v)])];
      v = parent[static_cast<std::size_t>(v)];
    }
    return v;
  };
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int c = 1; c < 3; ++c) {
      const int a = find(mesh.F(f, 0)), b = find(mesh.F(f, c));
      if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    }
  MeshShells shells;
  std::vector<int> shell_of_root(parent.size(), -1);
  shells.shell_of_face.resize(static_cast<std::size_t>(mesh.F.rows()));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    int& id = shell_of_root[static_cast<std::size_t>(find(mesh.F(f, 0)))];
    if (id < 0) {
      id = shells.count++;
      shells.volume.push_back(0.0);
    }
    shells.shell_of_face[static_cast<std::size_t>(f)] = id;
    const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)).transpose() - origin;
    const Eigen::Vector3d b = mesh.V.row(mesh.F(f, 1)).transpose() - origin;
    const Eigen::Vector3d c = mesh.V.row(mesh.F(f, 2)).transpose() - origin;
    shells.volume[static_cast<std::size_t>(id)] += a.dot(b.cross(c)) / 6.0;
  }
  return shells;
}

}  // namespace offsetopt
