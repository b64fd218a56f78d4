// Reading a mesh file as it is, before any validation or repair: the layer under load_mesh
// (which repairs and refuses) and `offsetopt check` (which reports every defect).
//
// A reader throws MeshInputError only for what it cannot represent: unreadable syntax, a
// truncated binary file, a header count the file cannot hold, a count above the caps below.
// Everything representable is kept as found, so validate_mesh can count it: non-finite
// coordinates, out-of-range vertex indices (kIndexOverflow when the index does not even fit in 32
// bits), degenerate or duplicate faces. Polygons are fan-triangulated (v0, vi, vi+1) with a
// warning (OBJ: non-convex polygons are ear-clipped in their plane instead). Vertex and face numbers count from 0 in file order (faces after triangulation).
//
// Limits, checked before anything of that size is allocated:
//   file size            <= kMaxFileBytes (2 GiB - 1, so line numbers fit in an int); only
//                        regular files are read
//   vertices             <= kMaxVertices (2^25 = 33,554,432)
//   triangles            <= kMaxFaces    (2^25, after triangulation)
//   polygon corners      any number in OBJ (split by our own ear clipping; a work cap refuses
//                        pathological outlines, meshio/read_obj.h)
// and a header count is only believed when the bytes left in the file can hold that many
// elements at their smallest encoding.
#pragma once
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "mesh/mesh.h"

namespace offsetopt {

constexpr std::uint64_t kMaxFileBytes = (std::uint64_t{1} << 31) - 1;
constexpr std::int64_t kMaxVertices = std::int64_t{1} << 25;
constexpr std::int64_t kMaxFaces = std::int64_t{1} << 25;
// Stored in F for a vertex index that does not fit in 32 bits (always out of range).
constexpr int kIndexOverflow = std::numeric_limits<int>::min();

enum class MeshFormat { obj, stl_ascii, stl_binary, off, ply_ascii, ply_binary_little, ply_binary_big, three_mf };

struct RawMesh {
  MeshFormat format = MeshFormat::obj;
  Vertices V;  // #V by 3, possibly non-finite
  Faces F;     // #F by 3, indices not yet checked against #V
  // Text formats: 1-based source line of each vertex and of the polygon each triangle came
  // from. Empty for binary formats (messages then name the vertex or face number only).
  std::vector<int> vertex_line;
  std::vector<int> face_line;
  std::vector<std::string> warnings;  // one line each, without "Warning: " or the file name
  std::string unit = {};  // the file's length unit when the format has one (3MF), else empty (an initializer, so aggregate initialisation without it does not warn)
};

// Human-readable name of a format ("binary STL", "ASCII PLY", ...).
const char* format_name(MeshFormat format);

// Reads the file at `path`: format chosen by extension (.obj .stl .off .ply .3mf, any case), or by
// content when the extension is unknown. Error messages start with `path` as given.
RawMesh read_raw_mesh(const std::string& path);

// The same for a file already in memory: `name` picks the format by its extension (by content
// when it has none) and starts every error message. read_raw_mesh(path) is this applied to
// read_file_capped(path); the fuzzers call it directly.
RawMesh read_raw_mesh_from_memory(const std::string& name, const std::string& bytes);

// Collects vertices and triangles while a reader runs, enforcing kMaxVertices and kMaxFaces and
// fan-triangulating polygons. `text_format` keeps source line numbers.
class RawMeshBuilder {
 public:
  RawMeshBuilder(const std::string& name, MeshFormat format, bool text_format);
  // Capacity hints; only pass counts already checked against the file size.
  void reserve(std::int64_t vertices, std::int64_t triangles);
  void add_vertex(double x, double y, double z, int line = 0);
  // A polygon of n >= 3 corners (indices as found, unchecked) becomes n - 2 triangles.
  void add_polygon(const int* corners, int n, int line = 0);
  // A polygon of n > 3 corners the reader split itself (OBJ: ear clipping in the polygon's
  // plane, meshio/triangulate_obj_face.h): `triangle_corners` holds 3 (n - 2) vertex indices.
  void add_polygon_triangles(const int* triangle_corners, int n, int line = 0);
  std::int64_t vertex_count() const { return static_cast<std::int64_t>(xyz_.size() / 3); }
  std::vector<std::string>& warnings() { return warnings_; }
  RawMesh finish();

 private:
  std::string name_;
  MeshFormat format_;
  bool text_format_;
  std::vector<double> xyz_;
  std::vector<int> corners_;
  std::vector<int> vertex_line_, face_line_;
  std::vector<std::string> warnings_;
  std::int64_t polygons_split_ = 0, triangles_from_polygons_ = 0;
  std::int64_t polygons_clipped_ = 0, triangles_from_clipping_ = 0;
};

// Reads the whole file into memory after checking it is a regular file within kMaxFileBytes.
std::string read_file_capped(const std::string& path);

}  // namespace offsetopt
