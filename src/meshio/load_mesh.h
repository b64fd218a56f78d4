// src/meshio: mesh files. The readers (OBJ, STL, OFF, PLY, 3MF, dispatched by read_raw_mesh.h,
// with the shared text scanning of read_text.h and the OBJ reader's polygon triangulation,
// triangulate_obj_face.h), the writers (write_mesh.h, write_3mf.h), validation as a printable solid
// (validate_mesh.h) and the input boundary every command goes through (load_mesh, this header).
// Layer: above geometry, beside io; it may include util/, optim/, mesh/, geometry/ and io/ (the
// zip and XML byte formats 3MF needs), nothing above (sparse, spectral, skeleton, mass, shape,
// cli). Library code: it returns values and throws MeshInputError, it never prints.
//
// The input boundary: read a mesh file of any supported format, validate it once, repair only
// what is safe, and refuse the rest with one line naming the file and the line or face.
// Every command goes through here; nothing after it re-validates.
#pragma once
#include <stdexcept>
#include <string>
#include <vector>

#include "mesh/mesh.h"
#include "meshio/read_raw_mesh.h"

namespace offsetopt {

// Thrown for input the program refuses. what() is one line: "<file>:<line>: <what is wrong>"
// for text formats, "<file>: <what is wrong>, face 17" (or vertex) otherwise, with the total
// count appended when there are several. The CLI prints it behind "Error: " and exits with 2.
class MeshInputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct LoadOptions {
  // Accept a consistently oriented mesh of negative volume by flipping every face (a warning).
  bool flip_inside_out = true;
  // Refuse a mesh of several components (separate shells, or a solid with cavities). Off by
  // default: such a mesh is accepted with a warning when every shell is closed and nested with
  // the right orientation (see the policy table in meshio/validate_mesh.h).
  bool single_component = false;
  // Threads for load_input's self-intersection search (meshio/load_input.h); the same result on
  // any count.
  int threads = 1;

  // Empty when valid, else what is wrong: every combination of these flags is valid, so always
  // empty (kept for the one convention of options structs).
  std::string check() const { return std::string(); }
};

struct LoadedMesh {
  Mesh mesh;  // a closed, consistently oriented 2-manifold of positive volume
  std::vector<std::string> warnings;  // one line each, without the "Warning: " prefix
  std::string format;                 // "OBJ", "binary STL", "ASCII PLY", ...
  std::string unit;                   // the file's length unit (3MF), else empty
  int components = 1;                 // closed shells (more than one only if allowed)
  // Back to the file's numbering, for messages about the loaded mesh (e.g. the CLI's
  // self-intersection and pinch warnings): file face and vertex number of each face and vertex
  // of `mesh` (empty when nothing was dropped: the numbers are the file's), and the source line
  // of each file face and vertex (text formats; empty otherwise).
  std::vector<long long> face_origin, vertex_origin;
  std::vector<int> face_line, vertex_line;
};

// Reads OBJ, STL (ascii/binary), OFF or PLY (ascii/binary), chosen by extension (by content when
// the extension is unknown), repairs what is safe and refuses the rest: the policy table is in
// meshio/validate_mesh.h. Warnings name what was repaired and where.
LoadedMesh load_mesh(const std::string& path, const LoadOptions& options = {});

// The same repair-or-refuse step for a mesh already read (`name` is used in messages).
LoadedMesh load_raw_mesh(const std::string& name, RawMesh raw, const LoadOptions& options = {});

}  // namespace offsetopt
