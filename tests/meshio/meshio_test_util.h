// Helpers for the mesh I/O tests: hand-made writers for the formats offsetopt only reads (ASCII
// STL, OFF, ASCII PLY, big-endian binary PLY), an independent edge census to check validation
// against, temporary files, and running the real binary.
#pragma once
#include <sys/wait.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "../support.h"
#include "../temp_dir.h"

#include "mesh/mesh.h"
#include "util/format_double.h"

namespace meshio_test {

using offsetopt::Mesh;

inline std::string number(double x) { return offsetopt::format_double(x); }

// Every coordinate rounded to float32, as STL stores it.
inline Mesh float_rounded(const Mesh& m) {
  Mesh out = m;
  for (Eigen::Index i = 0; i < out.V.rows(); ++i)
    for (int c = 0; c < 3; ++c) out.V(i, c) = static_cast<double>(static_cast<float>(out.V(i, c)));
  return out;
}

// Vertices renumbered in order of first use by the faces (the order an STL reader produces);
// unreferenced vertices dropped.
inline Mesh first_use_order(const Mesh& m) {
  std::vector<int> map(static_cast<std::size_t>(m.V.rows()), -1);
  std::vector<int> order;
  Mesh out;
  out.F.resize(m.F.rows(), 3);
  for (Eigen::Index f = 0; f < m.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      int& slot = map[static_cast<std::size_t>(m.F(f, c))];
      if (slot < 0) {
        slot = static_cast<int>(order.size());
        order.push_back(m.F(f, c));
      }
      out.F(f, c) = slot;
    }
  out.V.resize(static_cast<Eigen::Index>(order.size()), 3);
  for (std::size_t i = 0; i < order.size(); ++i) out.V.row(static_cast<Eigen::Index>(i)) = m.V.row(order[i]);
  return out;
}

// Bit-for-bit equality of coordinates (not ==, which equates -0 and 0 and fails on NaN).
inline bool identical(const Mesh& a, const Mesh& b) {
  if (a.V.rows() != b.V.rows() || a.F.rows() != b.F.rows()) return false;
  if (a.F != b.F) return false;
  return a.V.rows() == 0 || std::memcmp(a.V.data(), b.V.data(), sizeof(double) * static_cast<std::size_t>(a.V.size())) == 0;
}

inline std::string ascii_stl(const Mesh& m) {
  std::string out = "solid test\n";
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    out += "  facet normal 0 0 0\n    outer loop\n";
    for (int c = 0; c < 3; ++c) {
      out += "      vertex";
      for (int k = 0; k < 3; ++k) out += " " + number(static_cast<double>(static_cast<float>(m.V(m.F(f, c), k))));
      out += "\n";
    }
    out += "    endloop\n  endfacet\n";
  }
  return out + "endsolid test\n";
}

inline std::string off_text(const Mesh& m) {
  std::string out = "OFF\n# hand-made for the round-trip test\n" + std::to_string(m.V.rows()) + " " +
                    std::to_string(m.F.rows()) + " 0\n";
  for (Eigen::Index i = 0; i < m.V.rows(); ++i)
    out += number(m.V(i, 0)) + " " + number(m.V(i, 1)) + " " + number(m.V(i, 2)) + "\n";
  for (Eigen::Index f = 0; f < m.F.rows(); ++f)
    out += "3 " + std::to_string(m.F(f, 0)) + " " + std::to_string(m.F(f, 1)) + " " + std::to_string(m.F(f, 2)) + "\n";
  return out;
}

inline std::string ascii_ply(const Mesh& m) {
  std::string out = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(m.V.rows()) +
                    "\nproperty double x\nproperty double y\nproperty double z\nelement face " +
                    std::to_string(m.F.rows()) + "\nproperty list uchar int vertex_indices\nend_header\n";
  for (Eigen::Index i = 0; i < m.V.rows(); ++i)
    out += number(m.V(i, 0)) + " " + number(m.V(i, 1)) + " " + number(m.V(i, 2)) + "\n";
  for (Eigen::Index f = 0; f < m.F.rows(); ++f)
    out += "3 " + std::to_string(m.F(f, 0)) + " " + std::to_string(m.F(f, 1)) + " " + std::to_string(m.F(f, 2)) + "\n";
  return out;
}

template <typename T>
void append_big_endian(std::string& out, T value) {
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  for (std::size_t i = 0; i < sizeof(T); ++i) out += static_cast<char>(bytes[sizeof(T) - 1 - i]);  // host is little-endian
}

// Big-endian binary PLY with double (or float) coordinates, ushort list counts, uint indices.
inline std::string big_endian_ply(const Mesh& m, bool float_coordinates) {
  const char* type = float_coordinates ? "float" : "double";
  std::string out = std::string("ply\nformat binary_big_endian 1.0\nelement vertex ") + std::to_string(m.V.rows()) +
                    "\nproperty " + type + " x\nproperty " + type + " y\nproperty " + type + " z\nelement face " +
                    std::to_string(m.F.rows()) + "\nproperty list ushort uint vertex_indices\nend_header\n";
  for (Eigen::Index i = 0; i < m.V.rows(); ++i)
    for (int k = 0; k < 3; ++k) {
      if (float_coordinates) append_big_endian(out, static_cast<float>(m.V(i, k)));
      else append_big_endian(out, m.V(i, k));
    }
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    append_big_endian(out, static_cast<std::uint16_t>(3));
    for (int k = 0; k < 3; ++k) append_big_endian(out, static_cast<std::uint32_t>(m.F(f, k)));
  }
  return out;
}

// Independent edge census by std::map: boundary, non-manifold and inconsistently oriented edges
// with the smallest face touching each kind.
struct EdgeCensus {
  long long boundary = 0, non_manifold = 0, inconsistent = 0, edges = 0;
  long long first_boundary_face = -1, first_non_manifold_face = -1, first_inconsistent_face = -1;
};

inline EdgeCensus edge_census(const Mesh& m) {
  std::map<std::pair<int, int>, std::vector<std::pair<long long, bool>>> uses;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int u = m.F(f, c), w = m.F(f, (c + 1) % 3);
      if (u == w) continue;
      uses[{std::min(u, w), std::max(u, w)}].push_back({f, u < w});
    }
  EdgeCensus out;
  auto note = [](long long& count, long long& first, long long face) {
    ++count;
    if (first < 0 || face < first) first = face;
  };
  for (const auto& [edge, list] : uses) {
    ++out.edges;
    long long smallest = list[0].first;
    for (const auto& u : list) smallest = std::min(smallest, u.first);
    if (list.size() == 1) note(out.boundary, out.first_boundary_face, smallest);
    else if (list.size() > 2) note(out.non_manifold, out.first_non_manifold_face, smallest);
    else if (list[0].second == list[1].second) note(out.inconsistent, out.first_inconsistent_face, smallest);
  }
  return out;
}

using offsetopt::test::read_file;
using offsetopt::test::RunResult;
using offsetopt::test::shell_quote;
using offsetopt::test::write_file;

// Runs the real offsetopt binary under `timeout 10`, stdout and stderr captured via files.
inline RunResult run_offsetopt(const std::string& arguments, const TempDir& dir) {
  const std::string out_path = dir.file("stdout.txt"), err_path = dir.file("stderr.txt");
  const std::string command = "timeout 10 " + shell_quote(OFFSETOPT_BINARY) + " " + arguments + " >" +
                              shell_quote(out_path) + " 2>" + shell_quote(err_path);
  const int status = std::system(command.c_str());
  RunResult r;
  r.exit_code = offsetopt::test::exit_code_of(status);
  r.out = read_file(out_path);
  r.err = read_file(err_path);
  return r;
}

inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) out.push_back(line);
  return out;
}

}  // namespace meshio_test
