#include "io/basis_files.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "util/format_double.h"

namespace offsetopt {

namespace {

void append_u32(std::string& out, std::uint32_t v) {
  for (int byte = 0; byte < 4; ++byte) out.push_back(static_cast<char>((v >> (8 * byte)) & 0xffu));
}

void append_u64(std::string& out, std::uint64_t v) {
  for (int byte = 0; byte < 8; ++byte) out.push_back(static_cast<char>((v >> (8 * byte)) & 0xffu));
}

void append_f64(std::string& out, double value) {
  std::uint64_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  append_u64(out, bits);
}

void append_f32(std::string& out, double value) {
  const float f = static_cast<float>(value);
  std::uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  append_u32(out, bits);
}

// Blue (-1) - white (0) - red (+1).
unsigned char channel(double level) { return static_cast<unsigned char>(std::floor(255.0 * level + 0.5)); }

}  // namespace

std::string eigenvectors_npy(const Eigen::MatrixXd& vectors) {
  std::string header = "{'descr': '<f8', 'fortran_order': False, 'shape': (" + std::to_string(vectors.rows()) + ", " +
                       std::to_string(vectors.cols()) + "), }";
  // Magic (6) + version (2) + header length (2) + header, padded with spaces and a final
  // newline to a multiple of 64 bytes.
  const std::size_t unpadded = 10 + header.size() + 1;
  header.append((64 - unpadded % 64) % 64, ' ');
  header.push_back('\n');
  std::string out("\x93NUMPY\x01\x00", 8);
  out.push_back(static_cast<char>(header.size() & 0xffu));
  out.push_back(static_cast<char>((header.size() >> 8) & 0xffu));
  out += header;
  out.reserve(out.size() + static_cast<std::size_t>(vectors.size()) * 8);
  for (Eigen::Index i = 0; i < vectors.rows(); ++i)
    for (Eigen::Index j = 0; j < vectors.cols(); ++j) append_f64(out, vectors(i, j));
  return out;
}

std::string eigenvectors_csv(const Eigen::MatrixXd& vectors) {
  std::string out;
  for (Eigen::Index j = 0; j < vectors.cols(); ++j) {
    if (j) out.push_back(',');
    out += "phi_" + std::to_string(j);
  }
  out.push_back('\n');
  for (Eigen::Index i = 0; i < vectors.rows(); ++i) {
    for (Eigen::Index j = 0; j < vectors.cols(); ++j) {
      if (j) out.push_back(',');
      append_double(out, vectors(i, j));
    }
    out.push_back('\n');
  }
  return out;
}

std::string matrix_market(const Eigen::SparseMatrix<double>& symmetric) {
  Eigen::Index entries = 0;
  for (Eigen::Index col = 0; col < symmetric.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(symmetric, col); it; ++it)
      if (it.row() >= col) ++entries;
  std::string out = "%%MatrixMarket matrix coordinate real symmetric\n";
  out += std::to_string(symmetric.rows()) + " " + std::to_string(symmetric.cols()) + " " + std::to_string(entries) + "\n";
  for (Eigen::Index col = 0; col < symmetric.outerSize(); ++col) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(symmetric, col); it; ++it) {
      if (it.row() < col) continue;
      out += std::to_string(it.row() + 1) + " " + std::to_string(col + 1) + " ";
      append_double(out, it.value());
      out.push_back('\n');
    }
  }
  return out;
}

std::string scalar_ply(const Mesh& mesh, const Eigen::VectorXd& values) {
  std::string out = "ply\nformat binary_little_endian 1.0\ncomment offsetopt basis: eigenvector as quality and colour\n";
  out += "element vertex " + std::to_string(mesh.V.rows()) + "\n";
  out += "property float x\nproperty float y\nproperty float z\nproperty float quality\n";
  out += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  out += "element face " + std::to_string(mesh.F.rows()) + "\n";
  out += "property list uchar int vertex_indices\nend_header\n";
  double largest = 0.0;
  for (Eigen::Index i = 0; i < values.size(); ++i) largest = std::max(largest, std::abs(values(i)));
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    for (int c = 0; c < 3; ++c) append_f32(out, mesh.V(i, c));
    append_f32(out, values(i));
    const double t = largest > 0.0 ? values(i) / largest : 0.0;
    const double fade = 1.0 - std::abs(t);
    out.push_back(static_cast<char>(t < 0.0 ? channel(fade) : 255));
    out.push_back(static_cast<char>(channel(fade)));
    out.push_back(static_cast<char>(t > 0.0 ? channel(fade) : 255));
  }
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    out.push_back(3);
    for (int c = 0; c < 3; ++c) append_u32(out, static_cast<std::uint32_t>(mesh.F(f, c)));
  }
  return out;
}

}  // namespace offsetopt
