// Writes a mesh as OBJ, binary STL, binary PLY or 3MF, chosen by the file's extension. Numbers
// are shortest round-trip text (OBJ, 3MF) or raw little-endian (STL float32, PLY float64), never
// locale-dependent, so equal meshes give byte-identical files.
#pragma once
#include <string>

#include "mesh/mesh.h"

namespace offsetopt {

// Throws MeshInputError (meshio/load_mesh.h) for an unsupported extension and std::runtime_error
// when the file cannot be written.
// `unit` is written into 3MF files (one of units_3mf() in meshio/write_3mf.h: the coordinates are
// not scaled, only labelled); the other formats carry no unit and ignore it.
void write_mesh(const std::string& path, const Mesh& mesh, const std::string& unit = "millimeter");

// How the coordinates of a file written with that extension read back: STL stores float32, so
// every coordinate comes back rounded to the nearest float; OBJ and 3MF store shortest
// round-trip text and PLY float64, so they come back exactly. Unknown extensions: exact.
enum class StoredPrecision { exact, float32 };
StoredPrecision stored_precision(const std::string& path);

// The same bytes write_mesh would put in a file with that extension.
std::string mesh_to_bytes(const std::string& extension, const Mesh& mesh, const std::string& unit = "millimeter");

}  // namespace offsetopt
