// Readers against writers: every written format reads back to the same mesh (bit-identical
// coordinates for the double formats, the float32-rounded mesh for STL), the hand-made formats
// offsetopt only reads agree with them, and writers are byte-deterministic and locale-free.
#include <doctest/doctest.h>

#include <clocale>
#include <locale>

#include "mesh/primitives.h"
#include "meshio/load_mesh.h"
#include "meshio/read_raw_mesh.h"
#include "meshio/write_mesh.h"
#include "meshio_test_util.h"

using namespace offsetopt;
using namespace meshio_test;

namespace {

std::vector<std::pair<std::string, Mesh>> test_meshes() {
  // Coordinates with full 53-bit mantissas (icosphere, torus) and a box with negative zero.
  Mesh box = make_box(Eigen::Vector3d(-0.0, -1.25, 1e-7), Eigen::Vector3d(3.0 / 7.0, 2.5, 1e5 / 3.0));
  return {{"icosphere", make_icosphere(1.3, 2)}, {"torus", make_torus(2.0, 0.7, 24, 12)}, {"box", box}};
}

Mesh read_back(const TempDir& dir, const std::string& name, const std::string& bytes) {
  const std::string path = dir.file(name);
  write_file(path, bytes);
  const RawMesh raw = read_raw_mesh(path);
  CHECK(raw.warnings.empty());
  return Mesh{raw.V, raw.F};
}

}  // namespace

TEST_CASE("written OBJ and binary PLY read back bit-identical, binary STL as float32") {
  TempDir dir;
  for (const auto& [label, mesh] : test_meshes()) {
    CAPTURE(label);
    CHECK(identical(read_back(dir, label + ".obj", mesh_to_bytes(".obj", mesh)), mesh));
    CHECK(identical(read_back(dir, label + ".ply", mesh_to_bytes(".ply", mesh)), mesh));
    const Mesh from_stl = read_back(dir, label + ".stl", mesh_to_bytes(".stl", mesh));
    CHECK(identical(from_stl, first_use_order(float_rounded(mesh))));
    CHECK(from_stl.V.rows() == mesh.V.rows());  // welding found every shared corner, merged nothing else
  }
}

TEST_CASE("hand-made ASCII STL, OFF, ASCII PLY and big-endian PLY give the same mesh as the writers") {
  TempDir dir;
  for (const auto& [label, mesh] : test_meshes()) {
    CAPTURE(label);
    const Mesh reference = mesh;
    const Mesh stl_reference = first_use_order(float_rounded(mesh));
    CHECK(identical(read_back(dir, label + "_ascii.stl", ascii_stl(mesh)), stl_reference));
    CHECK(identical(read_back(dir, label + "_hand.off", off_text(mesh)), reference));
    CHECK(identical(read_back(dir, label + "_ascii.ply", ascii_ply(mesh)), reference));
    CHECK(identical(read_back(dir, label + "_be.ply", big_endian_ply(mesh, false)), reference));
    CHECK(identical(read_back(dir, label + "_be_float.ply", big_endian_ply(mesh, true)), float_rounded(reference)));
    // The two STL flavours agree with each other too.
    CHECK(identical(read_back(dir, label + "_bin.stl", mesh_to_bytes(".stl", mesh)),
                    read_back(dir, label + "_ascii2.stl", ascii_stl(mesh))));
  }
}

TEST_CASE("load_mesh accepts every written format of a valid mesh without a warning") {
  TempDir dir;
  const Mesh mesh = make_torus(2.0, 0.7, 24, 12);
  for (const char* ext : {".obj", ".stl", ".ply"}) {
    CAPTURE(ext);
    const std::string path = dir.file(std::string("torus") + ext);
    write_mesh(path, mesh);
    const LoadedMesh loaded = load_mesh(path);
    CHECK(loaded.warnings.empty());
    CHECK(loaded.components == 1);
    CHECK(loaded.mesh.F.rows() == mesh.F.rows());
    CHECK(loaded.mesh.V.rows() == mesh.V.rows());
  }
  CHECK_THROWS_WITH_AS(write_mesh(dir.file("torus.xyz"), mesh), doctest::Contains("unsupported output extension"),
                       MeshInputError);
  // Extensions are case-insensitive on both sides.
  write_mesh(dir.file("TORUS.OBJ"), mesh);
  CHECK(identical(Mesh{read_raw_mesh(dir.file("TORUS.OBJ")).V, read_raw_mesh(dir.file("TORUS.OBJ")).F}, mesh));
}

TEST_CASE("writers are byte-deterministic and print shortest round-trip numbers") {
  TempDir dir;
  const Mesh mesh = make_icosphere(0.7, 1);
  for (const char* ext : {".obj", ".stl", ".ply"}) {
    CAPTURE(ext);
    const std::string a = dir.file(std::string("a") + ext), b = dir.file(std::string("b") + ext);
    write_mesh(a, mesh);
    write_mesh(b, mesh);
    CHECK(read_file(a) == read_file(b));
    CHECK(read_file(a) == mesh_to_bytes(ext, mesh));
  }
  Mesh small;
  small.V.resize(3, 3);
  small.V << 0.1, 1.0 / 3.0, -2.5, 1e-300, 1e21, -0.0, 123456789.125, 5e-324, 0.30000000000000004;
  small.F.resize(1, 3);
  small.F << 0, 2, 1;
  CHECK(mesh_to_bytes(".obj", small) ==
        "# written by offsetopt\n"
        "v 0.1 0.3333333333333333 -2.5\n"
        "v 1e-300 1e+21 -0\n"
        "v 123456789.125 5e-324 0.30000000000000004\n"
        "f 1 3 2\n");
  const std::string stl = mesh_to_bytes(".stl", small);
  CHECK(stl.size() == 84 + 50);
  CHECK(stl.compare(0, 5, "solid") != 0);  // never mistaken for ASCII STL
  const std::string ply = mesh_to_bytes(".ply", small);
  CHECK(ply.size() == ply.find("end_header\n") + 11 + 3 * 24 + 13);
}

namespace {

// A numpunct with a comma decimal point and digit grouping, as a German locale has.
struct CommaNumpunct : std::numpunct<char> {
  char do_decimal_point() const override { return ','; }
  char do_thousands_sep() const override { return '.'; }
  std::string do_grouping() const override { return "\3"; }
};

}  // namespace

TEST_CASE("writing and reading do not depend on the locale") {
  TempDir dir;
  const Mesh mesh = make_torus(1234.5, 0.7, 12, 8);
  std::vector<std::string> classic;
  for (const char* ext : {".obj", ".stl", ".ply"}) classic.push_back(mesh_to_bytes(ext, mesh));
  const std::locale previous = std::locale::global(std::locale(std::locale::classic(), new CommaNumpunct));
  // The C library locale too, when the machine has a comma-decimal locale installed.
  const char* c_locale = nullptr;
  for (const char* name : {"de_DE.UTF-8", "de_DE.utf8", "fr_FR.UTF-8", "fr_FR.utf8"})
    if ((c_locale = std::setlocale(LC_ALL, name)) != nullptr) break;
  if (!c_locale) MESSAGE("no comma-decimal C locale installed; only the C++ global locale is changed");
  std::vector<std::string> localised;
  for (const char* ext : {".obj", ".stl", ".ply"}) localised.push_back(mesh_to_bytes(ext, mesh));
  write_file(dir.file("torus.obj"), classic[0]);
  const RawMesh raw = read_raw_mesh(dir.file("torus.obj"));
  write_file(dir.file("torus.off"), off_text(mesh));
  const RawMesh raw_off = read_raw_mesh(dir.file("torus.off"));
  std::setlocale(LC_ALL, "C");
  std::locale::global(previous);
  CHECK(localised == classic);
  CHECK(identical(Mesh{raw.V, raw.F}, mesh));
  CHECK(identical(Mesh{raw_off.V, raw_off.F}, mesh));
}

TEST_CASE("polygons are fan-triangulated with a warning in OBJ, OFF and PLY") {
  TempDir dir;
  // A pentagonal prism: two pentagons and five quads.
  std::string obj, off = "OFF\n10 7 0\n", ply = "ply\nformat ascii 1.0\nelement vertex 10\nproperty float x\n"
                                               "property float y\nproperty float z\nelement face 7\n"
                                               "property list uchar int vertex_indices\nend_header\n";
  const double xy[5][2] = {{2, 0}, {1, 2}, {-1, 2}, {-2, 0}, {0, -2}};
  for (int z = 0; z < 2; ++z)
    for (const auto& p : xy) {
      const std::string v = number(p[0]) + " " + number(p[1]) + " " + std::to_string(z);
      obj += "v " + v + "\n";
      off += v + "\n";
      ply += v + "\n";
    }
  std::vector<std::vector<int>> faces = {{0, 4, 3, 2, 1}, {5, 6, 7, 8, 9}};
  for (int i = 0; i < 5; ++i) faces.push_back({i, (i + 1) % 5, 5 + (i + 1) % 5, 5 + i});
  for (const auto& f : faces) {
    obj += "f";
    off += std::to_string(f.size());
    ply += std::to_string(f.size());
    for (int i : f) {
      obj += " " + std::to_string(i + 1);
      off += " " + std::to_string(i);
      ply += " " + std::to_string(i);
    }
    obj += "\n";
    off += "\n";
    ply += "\n";
  }
  for (const auto& [name, text] : {std::pair<std::string, std::string>{"prism.obj", obj}, {"prism.off", off}, {"prism.ply", ply}}) {
    CAPTURE(name);
    write_file(dir.file(name), text);
    const LoadedMesh loaded = load_mesh(dir.file(name));
    REQUIRE(loaded.warnings.size() == 1);
    CHECK(loaded.warnings[0] == "7 polygons with more than 3 corners fan-triangulated into 16 triangles");
    REQUIRE(loaded.mesh.F.rows() == 16);
    CHECK(loaded.mesh.F.row(0) == Eigen::RowVector3i(0, 4, 3));  // fan from the first corner
    CHECK(loaded.mesh.F.row(1) == Eigen::RowVector3i(0, 3, 2));
    CHECK(loaded.mesh.F.row(2) == Eigen::RowVector3i(0, 2, 1));
  }
}

TEST_CASE("STL welding merges exactly coincident corners only, including -0 with +0") {
  TempDir dir;
  // A tetrahedron whose corners are written with -0 in one facet and +0 in the others, plus
  // corners 1 ulp apart that must stay separate.
  std::string stl = "solid t\n";
  auto facet = [&stl](const char* a, const char* b, const char* c) {
    stl += std::string("facet normal 0 0 0\nouter loop\nvertex ") + a + "\nvertex " + b + "\nvertex " + c +
           "\nendloop\nendfacet\n";
  };
  facet("0 0 0", "0 1 0", "1 0 0");
  facet("-0 0 -0", "1 0 0", "0 0 1");
  facet("0 0 0", "0 0 1", "0 1 0");
  facet("1 0 0", "0 1 0", "0 0 1");
  stl += "endsolid t\n";
  write_file(dir.file("tet.stl"), stl);
  const RawMesh raw = read_raw_mesh(dir.file("tet.stl"));
  CHECK(raw.V.rows() == 4);
  CHECK(raw.format == MeshFormat::stl_ascii);
  CHECK(raw.face_line == std::vector<int>({2, 9, 16, 23}));
  const std::string near = "solid n\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                           "endloop\nendfacet\nfacet normal 0 0 0\nouter loop\nvertex 1.0000001 0 0\nvertex 0 0 0\n"
                           "vertex 0 0 1\nendloop\nendfacet\nendsolid n\n";
  write_file(dir.file("near.stl"), near);
  CHECK(read_raw_mesh(dir.file("near.stl")).V.rows() == 5);
}

TEST_CASE("binary STL is recognised by size, not by the word solid") {
  TempDir dir;
  const Mesh mesh = make_icosphere(1.0, 1);
  std::string bytes = mesh_to_bytes(".stl", mesh);
  bytes.replace(0, 11, "solid ascii");  // a binary file pretending to be ASCII in its header
  write_file(dir.file("solid.stl"), bytes);
  const RawMesh raw = read_raw_mesh(dir.file("solid.stl"));
  CHECK(raw.format == MeshFormat::stl_binary);
  CHECK(identical(Mesh{raw.V, raw.F}, first_use_order(float_rounded(mesh))));
  // Unknown extension: recognised by content.
  write_file(dir.file("mesh.bin"), bytes);
  CHECK(read_raw_mesh(dir.file("mesh.bin")).format == MeshFormat::stl_binary);
  write_file(dir.file("mesh.dat"), mesh_to_bytes(".ply", mesh));
  CHECK(read_raw_mesh(dir.file("mesh.dat")).format == MeshFormat::ply_binary_little);
  write_file(dir.file("mesh.txt"), off_text(mesh));
  CHECK(read_raw_mesh(dir.file("mesh.txt")).format == MeshFormat::off);
  write_file(dir.file("mesh"), mesh_to_bytes(".obj", mesh));
  CHECK(read_raw_mesh(dir.file("mesh")).format == MeshFormat::obj);
  write_file(dir.file("notes.txt"), "hello\n");
  CHECK_THROWS_WITH_AS(read_raw_mesh(dir.file("notes.txt")), doctest::Contains("unrecognised mesh format"), MeshInputError);
}

TEST_CASE("real meshes in the shared folder load with the vertex and face counts their README states") {
  const std::string folder = (offsetopt::test::shared_dir() / "meshes").string();
  if (!std::filesystem::exists(folder + "/README.md")) {
    offsetopt::test::skip_test(folder + "/README.md is absent");
    return;
  }
  struct Expected {
    const char* file;
    long long vertices, faces;
  };
  // From the shared folder's meshes/README.md.
  const Expected expected[] = {{"kitten_lowres.obj", 750, 1500},  {"rocker_arm.off", 800, 1600},
                               {"elephant.off", 2775, 5558},      {"fertility.off", 4494, 9000},
                               {"camel.off", 9770, 19536},        {"armadillo.off", 26002, 52000},
                               {"horse.ply", 48485, 96966},       {"Armadillo.ply", 172974, 345944},
                               {"20mm-xyz-cube.stl", 132, 260},   {"hinge.stl", 598, 1212},
                               {"spinit_kitten.obj", 3187, 6374}, {"spinit_dolphin.obj", 2562, 5120}};
  for (const Expected& e : expected) {
    CAPTURE(e.file);
    const LoadedMesh loaded = load_mesh(folder + "/" + e.file);
    CHECK(loaded.mesh.V.rows() == e.vertices);
    CHECK(loaded.mesh.F.rows() == e.faces);
    CHECK(loaded.components == 1);
    // horse.ply is stored inside-out (normals inwards); load_mesh flips it and says so.
    if (std::string(e.file) == "horse.ply") {
      REQUIRE(loaded.warnings.size() == 1);
      CHECK(loaded.warnings[0].find("inside-out") != std::string::npos);
    } else {
      CHECK(loaded.warnings.empty());
    }
  }
}
