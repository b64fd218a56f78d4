// TEMPORARY minimal implementation (OBJ only) so other modules can link; the mesh I/O issue
// replaces this file.
#include "mesh/write_mesh.h"

#include <fstream>

#include "mesh/load_mesh.h"
#include "util/format_double.h"

namespace offsetopt {

std::string mesh_to_bytes(const std::string& extension, const Mesh& mesh) {
  if (extension != ".obj") throw MeshInputError("unsupported output extension '" + extension + "'");
  std::string out;
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    out += "v";
    for (int c = 0; c < 3; ++c) { out += ' '; append_double(out, mesh.V(i, c)); }
    out += '\n';
  }
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    out += "f " + std::to_string(mesh.F(f, 0) + 1) + ' ' + std::to_string(mesh.F(f, 1) + 1) + ' ' + std::to_string(mesh.F(f, 2) + 1) + '\n';
  return out;
}

void write_mesh(const std::string& path, const Mesh& mesh) {
  const auto dot = path.rfind('.');
  const std::string bytes = mesh_to_bytes(dot == std::string::npos ? "" : path.substr(dot), mesh);
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error(path + ": cannot open for writing");
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error(path + ": write failed");
}

}  // namespace offsetopt
