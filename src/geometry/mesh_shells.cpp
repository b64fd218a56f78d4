#include "geometry/mesh_shells.h"

#include <Eigen/Geometry>

#include "util/disjoint_sets.h"
#include "util/neumaier_sum.h"

namespace offsetopt {

MeshShells mesh_shells(const Mesh& mesh, const Eigen::Vector3d& origin, const MeshShellsOptions& options) {
  DisjointSets vertex_sets(static_cast<std::size_t>(mesh.V.rows()));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int c = 1; c < 3; ++c)
      vertex_sets.unite(static_cast<std::uint32_t>(mesh.F(f, 0)), static_cast<std::uint32_t>(mesh.F(f, c)));
  MeshShells shells;
  std::vector<int> shell_of_root(vertex_sets.size(), -1);
  std::vector<NeumaierSum> six_volume;  // compensated only
  shells.shell_of_face.resize(static_cast<std::size_t>(mesh.F.rows()));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    int& id = shell_of_root[vertex_sets.find(static_cast<std::uint32_t>(mesh.F(f, 0)))];
    if (id < 0) {
      id = shells.count++;
      shells.volume.push_back(0.0);
      if (options.compensated) six_volume.emplace_back();
    }
    shells.shell_of_face[static_cast<std::size_t>(f)] = id;
    const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)).transpose() - origin;
    const Eigen::Vector3d b = mesh.V.row(mesh.F(f, 1)).transpose() - origin;
    const Eigen::Vector3d c = mesh.V.row(mesh.F(f, 2)).transpose() - origin;
    if (options.compensated) six_volume[static_cast<std::size_t>(id)].add(a.dot(b.cross(c)));
    else shells.volume[static_cast<std::size_t>(id)] += a.dot(b.cross(c)) / 6.0;
  }
  if (options.compensated) {
    NeumaierSum total;
    for (int s = 0; s < shells.count; ++s) {
      shells.volume[static_cast<std::size_t>(s)] = six_volume[static_cast<std::size_t>(s)].value() / 6.0;
      total.add(six_volume[static_cast<std::size_t>(s)].value());
    }
    shells.total_volume = total.value() / 6.0;
  } else {
    for (double v : shells.volume) shells.total_volume += v;
  }
  return shells;
}

}  // namespace offsetopt
