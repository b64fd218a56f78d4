// The input boundary: read a mesh file of any supported format, validate it once, repair only
// what is safe, and refuse the rest with one line naming the file and the line or face.
// Every command goes through here; nothing after it re-validates.
#pragma once
#include <stdexcept>
#include <string>
#include <vector>

#include "mesh/mesh.h"

namespace offsetopt {

// Thrown for input the program refuses. what() is one line: "<file>: <what is wrong>[, <where>]".
// The CLI prints it behind "Error: " and exits with code 2.
class MeshInputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct LoadOptions {
  // Accept a consistently oriented mesh of negative volume by flipping every face (a warning).
  bool flip_inside_out = true;
};

struct LoadedMesh {
  Mesh mesh;
  std::vector<std::string> warnings;  // one line each, without the "Warning: " prefix
};

// Reads OBJ, STL (ascii/binary), OFF or PLY (ascii/binary), chosen by content and extension.
LoadedMesh load_mesh(const std::string& path, const LoadOptions& options = {});

}  // namespace offsetopt
