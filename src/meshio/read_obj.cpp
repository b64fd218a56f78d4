#include "meshio/read_obj.h"

#define TINYOBJLOADER_IMPLEMENTATION
#define TINYOBJLOADER_USE_DOUBLE
#include <tiny_obj_loader.h>

#include <istream>
#include <streambuf>

#include "meshio/load_mesh.h"
#include "meshio/read_text.h"
#include "meshio/triangulate_obj_face.h"

namespace offsetopt {

namespace {

// tinyobjloader stores a face's corner count in a byte: longer faces are kept out of its copy.
constexpr std::size_t kTinyobjMaxCorners = 255;
// Point tests the ear clipping of one file may spend (about a second); beyond, the polygon is
// refused rather than triangulated wrongly.
constexpr long long kTriangulationBudget = 400000000;

// Serves the bytes of a string to an istream without copying them.
class MemoryBuffer : public std::streambuf {
 public:
  explicit MemoryBuffer(const std::string& text) {
    char* begin = const_cast<char*>(text.data());  // read-only use: the get area is never written
    setg(begin, begin, begin + text.size());
  }
};

// Refuses every material library: an OBJ may name any path (`mtllib ../../dev/zero`).
class RefuseMaterials : public tinyobj::MaterialReader {
 public:
  bool operator()(const std::string&, std::vector<tinyobj::material_t>*, std::map<std::string, int>*,
                  std::string*, std::string*) override {
    return false;
  }
};

[[noreturn]] void fail(const std::string& name, int line, const std::string& what) {
  throw MeshInputError(name + ":" + std::to_string(line) + ": " + what);
}

// Index part of a face corner: whole decimal integer, not 0.
std::int64_t parse_corner_index(const std::string& name, int line, std::string_view token, std::string_view part,
                                bool& overflow) {
  std::int64_t value = 0;
  if (!parse_integer(part, value, overflow))
    fail(name, line, "face corner '" + quote_bytes(token) + "' is not an index (v, v/vt, v/vt/, v//, v//vn or v/vt/vn)");
  if (!overflow && value == 0) fail(name, line, "index 0 in face corner '" + quote_bytes(token) + "' (OBJ counts from 1)");
  return value;
}

// One resolved vertex index of face corner `token`; texture and normal indices are checked
// for syntax only (they are not used).
int parse_corner(const std::string& name, int line, std::string_view token, std::int64_t vertices_so_far) {
  std::string_view parts[3];
  int part_count = 0;
  std::size_t start = 0;
  for (;;) {
    const std::size_t slash = token.find('/', start);
    if (part_count == 3) fail(name, line, "face corner '" + quote_bytes(token) + "' has more than three parts");
    parts[part_count++] = token.substr(start, slash == std::string_view::npos ? std::string_view::npos : slash - start);
    if (slash == std::string_view::npos) break;
    start = slash + 1;
  }
  bool overflow = false;
  const std::int64_t v = parse_corner_index(name, line, token, parts[0], overflow);
  // Texture and normal parts may be empty: `v/vt/` and `v//` are common exporter dialects.
  for (int k = 1; k < part_count; ++k) {
    bool ignored = false;
    if (!parts[k].empty()) parse_corner_index(name, line, token, parts[k], ignored);
  }
  if (overflow) return kIndexOverflow;
  const std::int64_t resolved = v > 0 ? v - 1 : vertices_so_far + v;
  if (resolved < std::numeric_limits<int>::min() + 1 || resolved > std::numeric_limits<int>::max()) return kIndexOverflow;
  return static_cast<int>(resolved);
}

}  // namespace

RawMesh read_obj(const std::string& name, const std::string& text) {
  refuse_nul_bytes(name, text);
  RawMeshBuilder builder(name, MeshFormat::obj, true);
  // Pass 1 (ours). `filtered` keeps only v and f lines for tinyobjloader, others blanked.
  std::string filtered;
  filtered.reserve(text.size());
  // Every polygon: resolved corner indices (flat), first corner, corner count, source line.
  std::vector<int> polygon_corners;
  std::vector<std::size_t> polygon_start;
  std::vector<int> polygon_line;
  std::vector<double> coordinates;  // our coordinates, for triangulating polygons in their plane
  // The polygons tinyobjloader also sees (at most kTinyobjMaxCorners corners), for the cross-check.
  std::vector<int> checked_sizes;
  std::vector<int> checked_corners;
  std::int64_t ignored_lines_points = 0;
  std::string material_library;
  LineScanner lines(text);
  std::string_view line;
  std::vector<std::string_view> tokens;
  while (lines.next(line)) {
    const int number = lines.line_number();
    split_tokens(line, tokens);
    if (tokens.empty() || tokens[0][0] == '#') {
      filtered += '\n';
      continue;
    }
    const std::string_view keyword = tokens[0];
    if (keyword == "v") {
      std::size_t count = tokens.size();
      for (std::size_t i = 1; i < tokens.size(); ++i)
        if (tokens[i][0] == '#') {
          count = i;
          break;
        }
      if (count < 4) fail(name, number, "vertex needs 3 coordinates, found " + std::to_string(count - 1));
      if (count > 8) fail(name, number, "vertex has " + std::to_string(count - 1) + " numbers (at most 7: x y z [w] [r g b])");
      double xyz[3] = {0, 0, 0};
      for (std::size_t i = 1; i < count; ++i) {
        double value = 0;
        if (!parse_real(tokens[i], value)) fail(name, number, "coordinate '" + quote_bytes(tokens[i]) + "' is not a number");
        if (i <= 3) xyz[i - 1] = value;
      }
      builder.add_vertex(xyz[0], xyz[1], xyz[2], number);
      coordinates.insert(coordinates.end(), xyz, xyz + 3);
      // tinyobjloader only cross-checks the faces and its number parser overflows an int on
      // exponents like 1e2147483648 (undefined behaviour): it gets a placeholder vertex.
      filtered += "v 0 0 0\n";
    } else if (keyword == "f") {
      const std::size_t n = tokens.size() - 1;
      for (std::size_t i = 1; i < tokens.size(); ++i)
        if (tokens[i][0] == '#') fail(name, number, "comment after face corners (not supported)");
      if (n < 3) fail(name, number, "face has " + std::to_string(n) + " corners (at least 3 needed)");
      const std::size_t start = polygon_corners.size();
      for (std::size_t i = 0; i < n; ++i)
        polygon_corners.push_back(parse_corner(name, number, tokens[i + 1], builder.vertex_count()));
      polygon_start.push_back(start);
      polygon_line.push_back(number);
      if (n <= kTinyobjMaxCorners) {
        // tinyobjloader sees the vertex part of each corner only (it has no use for the rest,
        // and it would read an empty `v/vt/` part as index 0).
        filtered += 'f';
        for (std::size_t i = 1; i <= n; ++i) {
          filtered += ' ';
          filtered.append(tokens[i].substr(0, tokens[i].find('/')));
        }
        checked_sizes.push_back(static_cast<int>(n));
        checked_corners.insert(checked_corners.end(), polygon_corners.begin() + static_cast<std::ptrdiff_t>(start), polygon_corners.end());
      }
      filtered += '\n';
    } else {
      if (keyword == "l" || keyword == "p") ++ignored_lines_points;
      if (keyword == "mtllib" && material_library.empty())
        material_library = tokens.size() > 1 ? std::string(tokens[1]) : std::string("(unnamed)");
      filtered += '\n';
    }
  }

  // Pass 2: tinyobjloader on the filtered copy, from memory, no material files, no triangulation.
  {
    MemoryBuffer buffer(filtered);
    std::istream stream(&buffer);
    RefuseMaterials no_materials;
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warn, err;
    const bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &stream, &no_materials,
                                     /*triangulate=*/false, /*default_vcols_fallback=*/false);
    if (!ok) {
      const std::string first = err.substr(0, err.find('\n'));
      throw MeshInputError(name + ": tinyobjloader refused the file: " + quote_bytes(first));
    }
    const std::int64_t vertices = builder.vertex_count();
    bool agree = static_cast<std::int64_t>(attrib.vertices.size()) == 3 * vertices;
    std::size_t polygon = 0, corner = 0;
    for (const auto& shape : shapes) {
      std::size_t index = 0;
      for (const unsigned char size : shape.mesh.num_face_vertices) {
        if (!agree) break;
        if (polygon >= checked_sizes.size() || size != checked_sizes[polygon]) {
          agree = false;
          break;
        }
        for (int k = 0; k < size; ++k, ++index, ++corner) {
          const int ours = checked_corners[corner];
          // Out-of-range indices are ours to report; only in-range ones must agree.
          if (ours >= 0 && ours < vertices && shape.mesh.indices[index].vertex_index != ours) agree = false;
        }
        ++polygon;
      }
    }
    if (!agree || polygon != checked_sizes.size()) {
      throw MeshInputError(name + ": OBJ readers disagree about the face list at face " + std::to_string(polygon) +
                           " (internal cross-check with tinyobjloader)");
    }
  }

  // Pass 3: triangles. Polygons whose corners all index a vertex are split in their own plane
  // (meshio/triangulate_obj_face.h); the others keep the fan, for validate_mesh to report.
  {
    const std::int64_t vertices = builder.vertex_count();
    long long budget = kTriangulationBudget;
    std::vector<Eigen::Vector3d> points;
    std::vector<int> local, triangles;
    polygon_start.push_back(polygon_corners.size());
    for (std::size_t p = 0; p + 1 < polygon_start.size(); ++p) {
      const int* corners = polygon_corners.data() + polygon_start[p];
      const int n = static_cast<int>(polygon_start[p + 1] - polygon_start[p]);
      bool in_range = true;
      for (int i = 0; i < n; ++i) in_range = in_range && corners[i] >= 0 && corners[i] < vertices;
      if (n == 3 || !in_range) {
        builder.add_polygon(corners, n, polygon_line[p]);
        continue;
      }
      points.resize(static_cast<std::size_t>(n));
      for (int i = 0; i < n; ++i)
        points[static_cast<std::size_t>(i)] = Eigen::Vector3d(coordinates[3 * static_cast<std::size_t>(corners[i])],
                                                              coordinates[3 * static_cast<std::size_t>(corners[i]) + 1],
                                                              coordinates[3 * static_cast<std::size_t>(corners[i]) + 2]);
      const PolygonTriangulationStatus how = triangulate_obj_face(points, local, budget);
      if (how == PolygonTriangulationStatus::budget_exhausted) {
        fail(name, polygon_line[p], "polygon of " + std::to_string(n) +
                                        " corners is too complex to triangulate (work cap of the ear clipping reached)");
      }
      if (how == PolygonTriangulationStatus::fan) {
        builder.add_polygon(corners, n, polygon_line[p]);
        continue;
      }
      triangles.resize(local.size());
      for (std::size_t k = 0; k < local.size(); ++k) triangles[k] = corners[local[k]];
      builder.add_polygon_triangles(triangles.data(), n, polygon_line[p]);
    }
  }

  if (ignored_lines_points > 0)
    builder.warnings().push_back(std::to_string(ignored_lines_points) + " line/point elements (l, p) ignored");
  if (!material_library.empty())
    builder.warnings().push_back("material library '" + quote_bytes(material_library) + "' not read (materials are ignored)");
  return builder.finish();
}

}  // namespace offsetopt
