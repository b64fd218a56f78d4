// The bad-input corpus (tests/data/bad/) and the accepted corpus (tests/data/accepted/), each
// with a table EXPECTED.txt (made by tests/meshio/make_corpus.py): the real binary must give the
// stated exit code and message, never crash or hang; load_mesh must refuse or accept the same way.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>

#include "meshio/load_mesh.h"
#include "meshio/read_raw_mesh.h"
#include "meshio/validate_mesh.h"
#include "meshio_test_util.h"

using namespace offsetopt;
using namespace meshio_test;

namespace {

const std::string kData = std::string(OFFSETOPT_SOURCE_DIR) + "/tests/data/";

std::vector<std::vector<std::string>> read_table(const std::string& path) {
  std::vector<std::vector<std::string>> rows;
  for (const std::string& line : lines_of(read_file(path))) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> fields;
    std::size_t start = 0;
    for (;;) {
      const std::size_t tab = line.find('\t', start);
      fields.push_back(line.substr(start, tab == std::string::npos ? std::string::npos : tab - start));
      if (tab == std::string::npos) break;
      start = tab + 1;
    }
    rows.push_back(fields);
  }
  return rows;
}

// Every file in the folder except the table is listed in it, and the other way round.
void check_table_covers_folder(const std::string& folder, const std::vector<std::vector<std::string>>& rows) {
  std::vector<std::string> listed, present;
  for (const auto& row : rows) listed.push_back(row[0]);
  for (const auto& entry : std::filesystem::directory_iterator(folder))
    if (entry.path().filename() != "EXPECTED.txt") present.push_back(entry.path().filename().string());
  std::sort(listed.begin(), listed.end());
  std::sort(present.begin(), present.end());
  CHECK(listed == present);
}

bool every_line_is_a_diagnostic(const std::string& err) {
  for (const std::string& line : lines_of(err))
    if (line.rfind("Error: ", 0) != 0 && line.rfind("Warning: ", 0) != 0) return false;
  return true;
}

}  // namespace

TEST_CASE("bad corpus: check exits 2 naming the defect, never crashes or hangs") {
  const auto rows = read_table(kData + "bad/EXPECTED.txt");
  REQUIRE(rows.size() >= 25);
  check_table_covers_folder(kData + "bad", rows);
  TempDir dir;
  for (const auto& row : rows) {
    REQUIRE(row.size() == 2);
    const std::string& file = row[0];
    const std::string& expected = row[1];
    CAPTURE(file);
    const RunResult r = run_offsetopt("check " + shell_quote(kData + "bad/" + file), dir);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find(expected) != std::string::npos);
    CHECK(r.err.find("Error: ") != std::string::npos);
    CHECK(every_line_is_a_diagnostic(r.err));
    CHECK(r.out.empty());
    INFO(r.err);
  }
}

TEST_CASE("bad corpus: strict load_mesh throws MeshInputError with the expected text") {
  LoadOptions strict;
  strict.flip_inside_out = false;
  strict.single_component = true;
  for (const auto& row : read_table(kData + "bad/EXPECTED.txt")) {
    CAPTURE(row[0]);
    const std::string path = kData + "bad/" + row[0];
    bool threw = false;
    try {
      load_mesh(path, strict);
    } catch (const MeshInputError& e) {
      threw = true;
      const std::string message = e.what();
      CAPTURE(message);
      CHECK(message.find(row[1]) != std::string::npos);
      CHECK(message.rfind(path, 0) == 0);  // starts with the file name
      CHECK(message.find('\n') == std::string::npos);
    }
    CHECK(threw);
  }
}

TEST_CASE("accepted corpus: load_mesh succeeds with the expected warning, and check gives the stated code") {
  const auto rows = read_table(kData + "accepted/EXPECTED.txt");
  check_table_covers_folder(kData + "accepted", rows);
  TempDir dir;
  for (const auto& row : rows) {
    REQUIRE(row.size() == 3);
    const std::string& file = row[0];
    CAPTURE(file);
    const std::string path = kData + "accepted/" + file;
    LoadedMesh loaded;
    REQUIRE_NOTHROW(loaded = load_mesh(path));
    std::string all_warnings;
    for (const std::string& w : loaded.warnings) all_warnings += w + "\n";
    CAPTURE(all_warnings);
    if (row[2] == "-") CHECK(loaded.warnings.empty());
    else CHECK(all_warnings.find(row[2]) != std::string::npos);
    // What load_mesh returns is a closed, oriented manifold of positive volume.
    const MeshValidation v = validate_mesh(loaded.mesh);
    for (const Defect& d : v.defects) CHECK(d.kind == DefectKind::several_components);
    CHECK(v.volume > 0);
    CHECK(v.unreferenced_vertices == 0);

    const RunResult r = run_offsetopt("check " + shell_quote(path), dir);
    CHECK(r.exit_code == std::stoi(row[1]));
    CHECK(every_line_is_a_diagnostic(r.err));
    if (r.exit_code == 0) {
      CHECK(r.out.find(path + ": ok: ") == 0);
      CHECK(lines_of(r.out).size() == 1);
    }
    INFO(r.err);
  }
}

TEST_CASE("check: usage, --quiet, --help, missing and unreadable files") {
  TempDir dir;
  const std::string cube = shell_quote(kData + "accepted/quads.obj");
  RunResult r = run_offsetopt("check " + cube, dir);
  CHECK(r.exit_code == 0);
  CHECK(r.out == kData + "accepted/quads.obj: ok: OBJ, 8 vertices, 12 faces, 18 edges, 1 component, genus 0, volume 1\n");
  CHECK(r.err.find("Warning: ") == 0);
  r = run_offsetopt("check --quiet " + cube, dir);
  CHECK(r.exit_code == 0);
  CHECK(r.out.empty());
  CHECK(r.err.empty());
  r = run_offsetopt("check --quiet " + shell_quote(kData + "bad/boundary_edges.obj"), dir);
  CHECK(r.exit_code == 2);
  CHECK(lines_of(r.err).size() == 1);
  r = run_offsetopt("check --help", dir);
  CHECK(r.exit_code == 0);
  CHECK(r.out.find("usage: offsetopt check MESH") == 0);
  r = run_offsetopt("check", dir);
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("Error: check: no mesh given") == 0);
  r = run_offsetopt("check --frobnicate " + cube, dir);
  CHECK(r.exit_code == 2);
  r = run_offsetopt("check " + shell_quote(dir.file("missing.obj")), dir);
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("cannot open file") != std::string::npos);
  r = run_offsetopt("check /dev/zero", dir);
  CHECK(r.exit_code == 2);
  CHECK(r.err == "Error: /dev/zero: not a regular file\n");
  r = run_offsetopt("check " + shell_quote(kData), dir);
  CHECK(r.exit_code == 2);
}

TEST_CASE("multi-line-defect file: one line per defect, each naming count and first index") {
  TempDir dir;
  const RunResult r = run_offsetopt("check " + shell_quote(kData + "bad/duplicate_face_opposite.obj"), dir);
  const std::string file = kData + "bad/duplicate_face_opposite.obj";
  CHECK(lines_of(r.err) == std::vector<std::string>{
                               "Error: " + file + ": duplicate faces: 1 (first: face 4, line 9): face repeats the vertices of face 0 (opposite orientation)",
                               "Error: " + file + ": non-manifold edges: 3 (first: face 0, line 5): edge 0-1 is shared by 3 faces"});
}

TEST_CASE("header counts beyond the file are refused before allocation") {
  // Counts near the caps in a tiny file: the reader must refuse from the header alone. (An
  // allocation of that size would still succeed here, so this checks the message and that the
  // refusal does not depend on reading the data.)
  TempDir dir;
  const std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex 33554432\nproperty double x\n"
                          "property double y\nproperty double z\nelement face 0\n"
                          "property list uchar int vertex_indices\nend_header\n";
  write_file(dir.file("big.ply"), ply);
  CHECK_THROWS_WITH_AS(read_raw_mesh(dir.file("big.ply")), doctest::Contains("more than the 0 bytes after the header can hold"),
                       MeshInputError);
  write_file(dir.file("big.off"), "OFF\n33554432 0 0\n");
  CHECK_THROWS_WITH_AS(read_raw_mesh(dir.file("big.off")), doctest::Contains("more than the remaining 0 bytes can hold"),
                       MeshInputError);
  write_file(dir.file("cap.off"), "OFF\n33554433 0 0\n");
  CHECK_THROWS_WITH_AS(read_raw_mesh(dir.file("cap.off")), doctest::Contains("the supported maximum is 33554432"),
                       MeshInputError);
  // A binary PLY face list whose count runs past the end of the data.
  std::string list = "ply\nformat binary_little_endian 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
                     "property float z\nelement face 1\n"
                     "property list uint int vertex_indices\nend_header\n";
  list += std::string("\xff\xff\xff\x0f", 4);
  write_file(dir.file("list.ply"), list);
  CHECK_THROWS_WITH_AS(read_raw_mesh(dir.file("list.ply")), doctest::Contains("truncated"), MeshInputError);
}
