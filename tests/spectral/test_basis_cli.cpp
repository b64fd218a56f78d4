// `offsetopt basis` end to end: report contents, vector files that read back to the solver's
// bits, byte-identical outputs across runs (timings aside), and usage errors (exit 2, one line).
#include <doctest/doctest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "../support.h"
#include "../test_meshes.h"
#include "io/json.h"
#include "meshio/load_mesh.h"
#include "spectral/manifold_harmonics.h"
#include "util/format_double.h"

using namespace offsetopt;
namespace fs = std::filesystem;

using offsetopt::test::read_file;

namespace {

struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() / ("offsetopt_basis_test_" + std::to_string(::getpid()));
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
  std::string operator/(const std::string& name) const { return (path / name).string(); }
};

void write_obj(const std::string& path, const Mesh& mesh) {
  std::string text;
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    text += "v";
    for (int c = 0; c < 3; ++c) {
      text += ' ';
      append_double(text, mesh.V(i, c));
    }
    text += '\n';
  }
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    text += "f " + std::to_string(mesh.F(f, 0) + 1) + ' ' + std::to_string(mesh.F(f, 1) + 1) + ' ' +
            std::to_string(mesh.F(f, 2) + 1) + '\n';
  std::ofstream(path, std::ios::binary) << text;
}

// Runs the binary with `arguments` (already quoted), stdout and stderr to files; exit code.
int run(const std::string& arguments, const std::string& out, const std::string& err) {
  const std::string command = std::string("'") + OFFSETOPT_BINARY + "' basis " + arguments + " >'" + out + "' 2>'" + err + "'";
  const int status = std::system(command.c_str());
  return offsetopt::test::exit_code_of(status);
}

Json without_timings(const Json& report) {
  Json copy = Json::object();
  for (const auto& [key, value] : report.items()) {
    if (key.size() >= 7 && key.compare(key.size() - 7, 7, "seconds") == 0) continue;
    copy.set(key, value);
  }
  return copy;
}

}  // namespace

TEST_CASE("basis CLI: report, vectors and PLY, and two runs write the same bytes apart from timings") {
  TempDir dir;
  const Mesh mesh = test::bumpy_icosphere(3);
  const std::string obj = dir / "bumpy.obj";
  write_obj(obj, mesh);
  const int k = 12;
  const std::string common = "'" + obj + "' --k " + std::to_string(k) + " --quiet";
  for (int round = 0; round < 2; ++round) {
    const std::string tag = std::to_string(round);
    REQUIRE(run(common + " --json '" + (dir / ("r" + tag + ".json")) + "' --vectors '" + (dir / ("v" + tag + ".npy")) +
                    "' --ply '" + (dir / ("p" + tag + ".ply")) + "' --ply-vector 3",
                dir / "out", dir / "err") == 0);
    REQUIRE(run(common + " --json - --vectors '" + (dir / ("v" + tag + ".csv")) + "' --basis laplacian", dir / ("stdout" + tag),
                dir / "err") == 0);
    CHECK(read_file(dir / "err").empty());  // --quiet
  }
  const Json first = Json::parse(read_file(dir / "r0.json"));
  const Json second = Json::parse(read_file(dir / "r1.json"));
  CHECK(without_timings(first).dump() == without_timings(second).dump());
  CHECK(read_file(dir / "v0.npy") == read_file(dir / "v1.npy"));
  CHECK(read_file(dir / "v0.csv") == read_file(dir / "v1.csv"));
  CHECK(read_file(dir / "p0.ply") == read_file(dir / "p1.ply"));
  CHECK(without_timings(Json::parse(read_file(dir / "stdout0"))).dump() ==
        without_timings(Json::parse(read_file(dir / "stdout1"))).dump());

  // Contents of the report.
  CHECK(first.at("status").as_string() == "converged");
  CHECK(first.at("basis").as_string() == "mass");
  CHECK(first.at("converged").as_integer() == k);
  CHECK(first.at("vertices").as_integer() == mesh.V.rows());
  REQUIRE(first.at("eigenvalues").size() == static_cast<std::size_t>(k));
  REQUIRE(first.at("residuals").size() == static_cast<std::size_t>(k));
  for (std::size_t j = 0; j < static_cast<std::size_t>(k); ++j) CHECK(first.at("residuals").at(j).as_number() <= 1e-10);
  CHECK(first.at("seconds").as_number() >= 0.0);
  CHECK(first.at("total_seconds").as_number() >= first.at("seconds").as_number());
  CHECK(first.at("operator_applications").as_integer() > 0);

  // The files hold exactly what the library computes for the mesh as read (an OBJ parser need not
  // round every coordinate back to the same bits).
  const Mesh loaded = load_mesh(obj).mesh;
  const LanczosResult library = manifold_harmonics(loaded, k);
  for (std::size_t j = 0; j < static_cast<std::size_t>(k); ++j)
    CHECK(first.at("eigenvalues").at(j).as_number() == library.eigenvalues(static_cast<Eigen::Index>(j)));
  const std::string npy = read_file(dir / "v0.npy");
  REQUIRE(npy.size() > 10);
  CHECK(npy.compare(0, 6, "\x93NUMPY") == 0);
  const std::size_t header_length = static_cast<unsigned char>(npy[8]) + 256u * static_cast<unsigned char>(npy[9]);
  CHECK((10 + header_length) % 64 == 0);
  const std::string header = npy.substr(10, header_length);
  CHECK(header.find("'descr': '<f8'") != std::string::npos);
  CHECK(header.find("'shape': (" + std::to_string(mesh.V.rows()) + ", " + std::to_string(k) + ")") != std::string::npos);
  REQUIRE(npy.size() == 10 + header_length + static_cast<std::size_t>(mesh.V.rows() * k) * 8);
  bool same = true;
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    for (int j = 0; j < k; ++j) {
      double value;
      std::memcpy(&value, npy.data() + 10 + header_length + 8 * (i * k + j), 8);
      same = same && value == library.eigenvectors(i, j);
    }
  }
  CHECK(same);
  // CSV of the Laplacian basis reads back to the library's doubles.
  ManifoldHarmonicsOptions laplacian;
  laplacian.kind = BasisKind::laplacian;
  const LanczosResult standard = manifold_harmonics(loaded, k, laplacian);
  std::istringstream csv(read_file(dir / "v0.csv"));
  std::string line;
  std::getline(csv, line);
  CHECK(line.rfind("phi_0,phi_1,", 0) == 0);
  Eigen::Index row = 0;
  bool csv_same = true;
  while (std::getline(csv, line)) {
    std::istringstream fields(line);
    std::string field;
    for (int j = 0; std::getline(fields, field, ','); ++j) csv_same = csv_same && std::strtod(field.c_str(), nullptr) == standard.eigenvectors(row, j);
    ++row;
  }
  CHECK(row == mesh.V.rows());
  CHECK(csv_same);
  // PLY: header, then 16 + 3 bytes per vertex and 13 per face.
  const std::string ply = read_file(dir / "p0.ply");
  const std::size_t end = ply.find("end_header\n");
  REQUIRE(end != std::string::npos);
  CHECK(ply.find("property float quality") < end);
  CHECK(ply.size() == end + 11 + static_cast<std::size_t>(mesh.V.rows()) * 19 + static_cast<std::size_t>(mesh.F.rows()) * 13);
  float quality;
  std::memcpy(&quality, ply.data() + end + 11 + 12, 4);  // vertex 0, after x y z
  CHECK(quality == static_cast<float>(library.eigenvectors(0, 3)));
}

TEST_CASE("basis CLI: usage errors exit 2 with one line") {
  TempDir dir;
  const std::string obj = dir / "ico.obj";
  write_obj(obj, make_icosphere(1.0, 1));  // 42 vertices
  struct Case {
    std::string arguments, expected;
  };
  const Case cases[] = {
      {"'" + obj + "'", "--k N is required"},
      {"'" + obj + "' --k 0", "--k must be in"},
      {"'" + obj + "' --k 42", "must be below the number of vertices (42)"},
      {"'" + obj + "' --k 100", "must be below the number of vertices (42)"},
      {"'" + obj + "' --k 5 --basis cotan", "--basis expects"},
      {"'" + obj + "' --k 5 --vectors out.txt", "must end in .npy or .csv"},
      {"'" + obj + "' --k 5 --ply-vector 2", "--ply-vector needs --ply"},
      {"'" + obj + "' --k 5 --ply a.ply --ply-vector 5", "must be below --k"},
      {"'" + obj + "' --k 5 --frobnicate", "unknown option"},
      {"'" + obj + "' --k 5 --json '" + obj + "'", "refusing to overwrite"},
      {"'" + (dir / "missing.obj") + "' --k 5", "missing.obj"},
      {"--k 5", "missing MESH"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.arguments);
    CHECK(run(c.arguments, dir / "out", dir / "err") == 2);
    const std::string err = read_file(dir / "err");
    CHECK(err.rfind("Error: ", 0) == 0);
    CHECK(err.find(c.expected) != std::string::npos);
    CHECK(std::count(err.begin(), err.end(), '\n') == 1);
  }
  CHECK(run("--help", dir / "out", dir / "err") == 0);
  CHECK(read_file(dir / "out").find("usage: offsetopt basis") != std::string::npos);
}
