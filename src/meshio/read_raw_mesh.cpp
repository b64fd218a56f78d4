#include "meshio/read_raw_mesh.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "meshio/load_mesh.h"
#include "meshio/read_3mf.h"
#include "meshio/read_obj.h"
#include "meshio/read_off.h"
#include "meshio/read_ply.h"
#include "meshio/read_stl.h"
#include "meshio/read_text.h"

namespace offsetopt {

const char* format_name(MeshFormat format) {
  switch (format) {
    case MeshFormat::obj: return "OBJ";
    case MeshFormat::stl_ascii: return "ASCII STL";
    case MeshFormat::stl_binary: return "binary STL";
    case MeshFormat::off: return "OFF";
    case MeshFormat::ply_ascii: return "ASCII PLY";
    case MeshFormat::ply_binary_little: return "binary little-endian PLY";
    case MeshFormat::ply_binary_big: return "binary big-endian PLY";
    case MeshFormat::three_mf: return "3MF";
  }
  return "unknown";
}

RawMeshBuilder::RawMeshBuilder(const std::string& name, MeshFormat format, bool text_format)
    : name_(name), format_(format), text_format_(text_format) {}

void RawMeshBuilder::reserve(std::int64_t vertices, std::int64_t triangles) {
  if (vertices > 0 && vertices <= kMaxVertices) {
    xyz_.reserve(static_cast<std::size_t>(3 * vertices));
    if (text_format_) vertex_line_.reserve(static_cast<std::size_t>(vertices));
  }
  if (triangles > 0 && triangles <= kMaxFaces) {
    corners_.reserve(static_cast<std::size_t>(3 * triangles));
    if (text_format_) face_line_.reserve(static_cast<std::size_t>(triangles));
  }
}

void RawMeshBuilder::add_vertex(double x, double y, double z, int line) {
  if (vertex_count() >= kMaxVertices) {
    throw MeshInputError(name_ + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": more than " +
                         std::to_string(kMaxVertices) + " vertices (the supported maximum)");
  }
  xyz_.push_back(x);
  xyz_.push_back(y);
  xyz_.push_back(z);
  if (text_format_) vertex_line_.push_back(line);
}

void RawMeshBuilder::add_polygon(const int* corners, int n, int line) {
  const std::int64_t triangles = static_cast<std::int64_t>(corners_.size() / 3);
  if (triangles + (n - 2) > kMaxFaces) {
    throw MeshInputError(name_ + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": more than " +
                         std::to_string(kMaxFaces) + " triangles (the supported maximum)");
  }
  for (int i = 1; i + 1 < n; ++i) {
    corners_.push_back(corners[0]);
    corners_.push_back(corners[i]);
    corners_.push_back(corners[i + 1]);
    if (text_format_) face_line_.push_back(line);
  }
  if (n > 3) {
    ++polygons_split_;
    triangles_from_polygons_ += n - 2;
  }
}

void RawMeshBuilder::add_polygon_triangles(const int* triangle_corners, int n, int line) {
  const std::int64_t triangles = static_cast<std::int64_t>(corners_.size() / 3);
  if (triangles + (n - 2) > kMaxFaces) {
    throw MeshInputError(name_ + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": more than " +
                         std::to_string(kMaxFaces) + " triangles (the supported maximum)");
  }
  corners_.insert(corners_.end(), triangle_corners, triangle_corners + 3 * (n - 2));
  if (text_format_) face_line_.insert(face_line_.end(), static_cast<std::size_t>(n - 2), line);
  ++polygons_clipped_;
  triangles_from_clipping_ += n - 2;
}

RawMesh RawMeshBuilder::finish() {
  RawMesh raw;
  raw.format = format_;
  const Eigen::Index nv = static_cast<Eigen::Index>(xyz_.size() / 3);
  const Eigen::Index nf = static_cast<Eigen::Index>(corners_.size() / 3);
  raw.V.resize(nv, 3);
  for (Eigen::Index i = 0; i < nv; ++i)
    for (int c = 0; c < 3; ++c) raw.V(i, c) = xyz_[static_cast<std::size_t>(3 * i + c)];
  std::vector<double>().swap(xyz_);
  raw.F.resize(nf, 3);
  for (Eigen::Index f = 0; f < nf; ++f)
    for (int c = 0; c < 3; ++c) raw.F(f, c) = corners_[static_cast<std::size_t>(3 * f + c)];
  std::vector<int>().swap(corners_);
  raw.vertex_line = std::move(vertex_line_);
  raw.face_line = std::move(face_line_);
  raw.warnings = std::move(warnings_);
  if (polygons_split_ > 0) {
    raw.warnings.push_back(std::to_string(polygons_split_) + (polygons_split_ == 1 ? " polygon" : " polygons") +
                           " with more than 3 corners fan-triangulated into " +
                           std::to_string(triangles_from_polygons_) + " triangles");
  }
  if (polygons_clipped_ > 0) {
    raw.warnings.push_back(std::to_string(polygons_clipped_) + (polygons_clipped_ == 1 ? " non-convex polygon" : " non-convex polygons") +
                           " triangulated by ear clipping in the polygon's plane into " +
                           std::to_string(triangles_from_clipping_) + " triangles");
  }
  return raw;
}

std::string read_file_capped(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throw MeshInputError(path + ": cannot open file (" + std::strerror(errno) + ")");
  struct FdCloser {
    int fd;
    ~FdCloser() { ::close(fd); }
  } closer{fd};
  struct stat info {};
  if (::fstat(fd, &info) != 0) throw MeshInputError(path + ": cannot stat file (" + std::strerror(errno) + ")");
  if (!S_ISREG(info.st_mode)) throw MeshInputError(path + ": not a regular file");
  const std::uint64_t size = static_cast<std::uint64_t>(info.st_size);
  if (size > kMaxFileBytes) {
    throw MeshInputError(path + ": file is " + std::to_string(size) + " bytes; the supported maximum is " +
                         std::to_string(kMaxFileBytes) + " (2 GiB - 1)");
  }
  std::string bytes(static_cast<std::size_t>(size), '\0');
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t got = ::read(fd, &bytes[done], bytes.size() - done);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) throw MeshInputError(path + ": read failed (" + std::strerror(errno) + ")");
    if (got == 0) break;  // the file shrank while we read it
    done += static_cast<std::size_t>(got);
  }
  bytes.resize(done);
  return bytes;
}

namespace {

std::string lower_extension(const std::string& path) {
  const auto slash = path.find_last_of('/');
  const auto dot = path.rfind('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot);
  for (char& c : ext)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return ext;
}

bool starts_with(const std::string& bytes, const char* prefix) {
  return bytes.compare(0, std::strlen(prefix), prefix) == 0;
}

}  // namespace

RawMesh read_raw_mesh(const std::string& path) { return read_raw_mesh_from_memory(path, read_file_capped(path)); }

RawMesh read_raw_mesh_from_memory(const std::string& path, const std::string& bytes) {
  if (bytes.size() > kMaxFileBytes) {
    throw MeshInputError(path + ": file is " + std::to_string(bytes.size()) + " bytes; the supported maximum is " +
                         std::to_string(kMaxFileBytes) + " (2 GiB - 1)");
  }
  if (bytes.empty()) throw MeshInputError(path + ": file is empty");
  const std::string ext = lower_extension(path);
  if (ext == ".obj") return read_obj(path, bytes);
  if (ext == ".stl") return read_stl(path, bytes);
  if (ext == ".off") return read_off(path, bytes);
  if (ext == ".ply") return read_ply(path, bytes);
  if (ext == ".3mf") return read_3mf(path, bytes);
  // Unknown extension: recognise the content by its signature.
  if (starts_with(bytes, "ply\n") || starts_with(bytes, "ply\r")) return read_ply(path, bytes);
  if (looks_like_zip(bytes)) return read_3mf(path, bytes);
  std::size_t first = bytes.find_first_not_of(" \t\r\n");
  if (first != std::string::npos) {
    const std::size_t end = bytes.find_first_of(" \t\r\n", first);
    const std::string word = bytes.substr(first, end == std::string::npos ? std::string::npos : end - first);
    if (word.size() >= 3 && word.compare(word.size() - 3, 3, "OFF") == 0) return read_off(path, bytes);
    if (equals_ignoring_case(word, "solid") || looks_like_binary_stl(bytes)) return read_stl(path, bytes);
  }
  // OBJ has no signature: accept it when the first statement is a typical OBJ keyword.
  {
    LineScanner lines(bytes);
    std::string_view line;
    std::vector<std::string_view> tokens;
    for (int i = 0; i < 1000 && lines.next(line); ++i) {
      split_tokens(line, tokens);
      if (tokens.empty() || tokens[0][0] == '#') continue;
      for (const char* keyword : {"v", "vn", "vt", "f", "o", "g", "s", "mtllib", "usemtl"})
        if (tokens[0] == keyword) return read_obj(path, bytes);
      break;
    }
  }
  throw MeshInputError(path + ": unrecognised mesh format (expected an .obj, .stl, .off, .ply or .3mf file)");
}

}  // namespace offsetopt
