// Writes a mesh as OBJ, binary STL or binary PLY, chosen by the file's extension. Numbers are
// shortest round-trip text (OBJ) or raw little-endian (STL float32, PLY float64), never
// locale-dependent, so equal meshes give byte-identical files.
#pragma once
#include <string>

#include "mesh/mesh.h"

namespace offsetopt {

// Throws MeshInputError (mesh/load_mesh.h) for an unsupported extension and std::runtime_error
// when the file cannot be written.
void write_mesh(const std::string& path, const Mesh& mesh);

// The same bytes write_mesh would put in a file with that extension.
std::string mesh_to_bytes(const std::string& extension, const Mesh& mesh);

}  // namespace offsetopt
