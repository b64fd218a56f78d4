#include "meshio/write_mesh.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>

#include <Eigen/Geometry>

#include "meshio/load_mesh.h"
#include "meshio/write_3mf.h"
#include "util/format_double.h"

namespace offsetopt {

namespace {

void append_u32_le(std::string& out, std::uint32_t value) {
  for (int i = 0; i < 4; ++i) out += static_cast<char>((value >> (8 * i)) & 0xff);
}

void append_u64_le(std::string& out, std::uint64_t value) {
  for (int i = 0; i < 8; ++i) out += static_cast<char>((value >> (8 * i)) & 0xff);
}

void append_f64_le(std::string& out, double value) {
  std::uint64_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  append_u64_le(out, bits);
}

std::string to_obj(const Mesh& mesh) {
  std::string out = "# written by offsetopt\n";
  out.reserve(static_cast<std::size_t>(mesh.V.rows()) * 64 + static_cast<std::size_t>(mesh.F.rows()) * 24);
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    out += 'v';
    for (int c = 0; c < 3; ++c) {
      out += ' ';
      append_double(out, mesh.V(i, c));
    }
    out += '\n';
  }
  char buffer[16];
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    out += 'f';
    for (int c = 0; c < 3; ++c) {
      out += ' ';
      // std::to_chars: locale-independent, like the coordinates.
      const auto end = std::to_chars(buffer, buffer + sizeof buffer, static_cast<long long>(mesh.F(f, c)) + 1).ptr;
      out.append(buffer, end);
    }
    out += '\n';
  }
  return out;
}

std::string to_binary_stl(const Mesh& mesh) {
  if (mesh.F.rows() > static_cast<Eigen::Index>(UINT32_MAX))
    throw MeshInputError("too many faces for binary STL (" + std::to_string(mesh.F.rows()) + ")");
  // The header must not start with "solid", or some readers take the file for ASCII STL.
  std::string out = "binary STL written by offsetopt";
  out.resize(80, ' ');
  out.reserve(84 + 50 * static_cast<std::size_t>(mesh.F.rows()));
  append_u32_le(out, static_cast<std::uint32_t>(mesh.F.rows()));
  // One 50-byte record per face, filled in place and appended whole (appending byte by byte
  // checked the capacity 50 times a face).
  char record[50] = {};
  auto put_f32 = [&record](int at, float value) {
    std::uint32_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    for (int i = 0; i < 4; ++i) record[at + i] = static_cast<char>((bits >> (8 * i)) & 0xff);
  };
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)), b = mesh.V.row(mesh.F(f, 1)), c = mesh.V.row(mesh.F(f, 2));
    Eigen::Vector3d n = (b - a).cross(c - a);
    const double length = std::sqrt(n.dot(n));
    if (length > 0) n /= length;
    else n.setZero();
    for (int k = 0; k < 3; ++k) put_f32(4 * k, static_cast<float>(n[k]));
    int at = 12;
    for (const Eigen::Vector3d* p : {&a, &b, &c})
      for (int k = 0; k < 3; ++k, at += 4) put_f32(at, static_cast<float>((*p)[k]));
    out.append(record, sizeof record);  // the last two bytes: attribute count 0
  }
  return out;
}

std::string to_binary_ply(const Mesh& mesh) {
  std::string out =
      "ply\n"
      "format binary_little_endian 1.0\n"
      "comment written by offsetopt\n"
      "element vertex " + std::to_string(mesh.V.rows()) + "\n"
      "property double x\n"
      "property double y\n"
      "property double z\n"
      "element face " + std::to_string(mesh.F.rows()) + "\n"
      "property list uchar int vertex_indices\n"
      "end_header\n";
  out.reserve(out.size() + 24 * static_cast<std::size_t>(mesh.V.rows()) + 13 * static_cast<std::size_t>(mesh.F.rows()));
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i)
    for (int c = 0; c < 3; ++c) append_f64_le(out, mesh.V(i, c));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    out += static_cast<char>(3);
    for (int c = 0; c < 3; ++c) append_u32_le(out, static_cast<std::uint32_t>(mesh.F(f, c)));
  }
  return out;
}

std::string lower(std::string text) {
  for (char& c : text)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return text;
}

}  // namespace

std::string mesh_to_bytes(const std::string& extension, const Mesh& mesh, const std::string& unit) {
  const std::string ext = lower(extension);
  if (ext == ".obj") return to_obj(mesh);
  if (ext == ".stl") return to_binary_stl(mesh);
  if (ext == ".ply") return to_binary_ply(mesh);
  if (ext == ".3mf") return write_3mf(mesh, unit);
  throw MeshInputError("unsupported output extension '" + extension + "' (use .obj, .stl, .ply or .3mf)");
}

StoredPrecision stored_precision(const std::string& path) {
  const auto slash = path.find_last_of('/');
  const auto dot = path.rfind('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return StoredPrecision::exact;
  return lower(path.substr(dot)) == ".stl" ? StoredPrecision::float32 : StoredPrecision::exact;
}

void write_mesh(const std::string& path, const Mesh& mesh, const std::string& unit) {
  const auto slash = path.find_last_of('/');
  const auto dot = path.rfind('.');
  const bool has_extension = dot != std::string::npos && (slash == std::string::npos || dot > slash);
  std::string bytes;
  try {
    bytes = mesh_to_bytes(has_extension ? path.substr(dot) : "", mesh, unit);
  } catch (const MeshInputError& e) {
    throw MeshInputError(path + ": " + e.what());
  }
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error(path + ": cannot open for writing");
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) throw std::runtime_error(path + ": write failed");
}

}  // namespace offsetopt
