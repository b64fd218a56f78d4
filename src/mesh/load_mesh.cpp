// TEMPORARY minimal implementation (OBJ only, no validation) so other modules can link; the
// mesh I/O issue replaces this file.
#include "mesh/load_mesh.h"

#define TINYOBJLOADER_IMPLEMENTATION
#define TINYOBJLOADER_USE_DOUBLE
#include <tiny_obj_loader.h>

#include <fstream>
#include <sstream>

namespace offsetopt {

LoadedMesh load_mesh(const std::string& path, const LoadOptions&) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw MeshInputError(path + ": cannot open file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  tinyobj::ObjReader reader;
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  if (!reader.ParseFromString(buffer.str(), "", config)) throw MeshInputError(path + ": " + reader.Error());
  const auto& attrib = reader.GetAttrib();
  LoadedMesh out;
  const Eigen::Index n = static_cast<Eigen::Index>(attrib.vertices.size() / 3);
  out.mesh.V.resize(n, 3);
  for (Eigen::Index i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) out.mesh.V(i, c) = attrib.vertices[static_cast<std::size_t>(3 * i + c)];
  std::vector<int> idx;
  for (const auto& shape : reader.GetShapes())
    for (const auto& index : shape.mesh.indices) idx.push_back(index.vertex_index);
  out.mesh.F.resize(static_cast<Eigen::Index>(idx.size() / 3), 3);
  for (std::size_t i = 0; i < idx.size(); ++i) out.mesh.F(static_cast<Eigen::Index>(i / 3), static_cast<int>(i % 3)) = idx[i];
  return out;
}

}  // namespace offsetopt
