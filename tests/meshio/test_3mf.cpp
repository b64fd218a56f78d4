// 3MF in and out (issue 14; CRC-32 and inflate are tested in tests/io/test_zip_formats.cpp): the
// written package against independent tools (unzip -t, python3's
// zipfile and xml.dom.minidom, each skipped when absent), a sphere-in-sphere solid that keeps its
// two shells and its mass properties through write and read, a package re-compressed with
// deflate by python3, and hostile packages built here.
#include <doctest/doctest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <string>
#include <string_view>

#include "io/xml_scanner.h"
#include "io/zip_archive.h"
#include "mass/mass_properties.h"
#include "mass/volume_integrals.h"
#include "mesh/primitives.h"
#include "meshio/load_mesh.h"
#include "meshio/read_raw_mesh.h"
#include "meshio/write_3mf.h"
#include "meshio/write_mesh.h"
#include "meshio_test_util.h"

using namespace offsetopt;
using namespace meshio_test;

namespace {

bool have(const char* program) { return ::access(program, X_OK) == 0; }

int shell(const std::string& command) {
  const int status = std::system(command.c_str());
  return offsetopt::test::exit_code_of(status);
}

// A solid sphere of radius 10 with a spherical cavity of radius 6 off its centre, moved away
// from the origin so no moment vanishes by symmetry: two closed shells, the inner one reversed.
Mesh sphere_in_sphere() {
  Mesh outer = make_icosphere(10.0, 3), inner = make_icosphere(6.0, 2);
  for (Eigen::Index i = 0; i < outer.V.rows(); ++i) outer.V.row(i) += Eigen::RowVector3d(1.25, -2.5, 10.0);
  for (Eigen::Index i = 0; i < inner.V.rows(); ++i) inner.V.row(i) += Eigen::RowVector3d(2.0, -2.0, 11.0);
  Mesh solid;
  solid.V.resize(outer.V.rows() + inner.V.rows(), 3);
  solid.V << outer.V, inner.V;
  solid.F.resize(outer.F.rows() + inner.F.rows(), 3);
  solid.F.topRows(outer.F.rows()) = outer.F;
  for (Eigen::Index f = 0; f < inner.F.rows(); ++f)
    solid.F.row(outer.F.rows() + f) = Eigen::RowVector3i(inner.F(f, 0), inner.F(f, 2), inner.F(f, 1)).array() + static_cast<int>(outer.V.rows());
  return solid;
}

Mesh from_raw(const RawMesh& raw) { return Mesh{raw.V, raw.F}; }

}  // namespace

TEST_CASE("3MF: a sphere-in-sphere solid keeps both shells and its mass properties through write and read") {
  const Mesh solid = sphere_in_sphere();
  const std::string bytes = write_3mf(solid);
  CHECK(bytes == write_3mf(solid));  // deterministic
  TempDir dir;
  const std::string path = dir.file("solid.3mf");
  write_mesh(path, solid);
  CHECK(read_file(path) == bytes);
  const RawMesh raw = read_raw_mesh(path);
  CHECK(raw.format == MeshFormat::three_mf);
  CHECK(raw.warnings.empty());
  CHECK(identical(from_raw(raw), solid));
  const Vector10d expected = mass_properties(volume_integrals(solid));
  const LoadedMesh loaded = load_mesh(path);
  CHECK(loaded.components == 2);  // outer shell and cavity, one object
  const Vector10d got = mass_properties(volume_integrals(loaded.mesh));
  for (int k = 0; k < 10; ++k) {
    CAPTURE(k);
    CHECK(std::abs(got(k) - expected(k)) <= 1e-12 * std::max(1.0, std::abs(expected(k))));
  }
  // The cavity is really there: the mass is the difference of the two balls' polyhedral volumes.
  CHECK(expected(kMass) < volume_integrals(make_icosphere(10.0, 3)).values(kIntVolume));

  SUBCASE("the zip and its XML pass independent checks") {
    std::vector<ZipEntryInfo> entries;
    std::string error;
    REQUIRE(list_zip(bytes, entries, error));
    REQUIRE(entries.size() == 3);
    CHECK(entries[0].name == "[Content_Types].xml");
    CHECK(entries[1].name == "_rels/.rels");
    CHECK(entries[2].name == "3D/3dmodel.model");
    for (const ZipEntryInfo& e : entries) {
      std::string data;
      REQUIRE(extract_zip_entry(bytes, e, 1 << 30, data, error));
      XmlScanner x(data);
      int elements = 0;
      while (x.next() && x.kind() != XmlTokenKind::eof) elements += x.kind() == XmlTokenKind::start;
      CHECK(x.error().empty());
      CHECK(elements >= 2);
      if (e.name == "3D/3dmodel.model") {
        CHECK(data.find("unit=\"millimeter\"") != std::string::npos);
        CHECK(data.find("xmlns=\"http://schemas.microsoft.com/3dmanufacturing/core/2015/02\"") != std::string::npos);
        std::size_t objects = 0;
        for (std::size_t at = data.find("<object "); at != std::string::npos; at = data.find("<object ", at + 1)) ++objects;
        CHECK(objects == 1);
      }
    }
    INFO("scripts/deps.sh installs unzip and python3");
    REQUIRE(have("/usr/bin/unzip"));
    CHECK(shell("/usr/bin/unzip -tq " + shell_quote(path) + " >/dev/null 2>&1") == 0);
    REQUIRE(have("/usr/bin/python3"));
    {
      const std::string script =
          "import sys, zipfile, xml.dom.minidom\n"
          "z = zipfile.ZipFile(sys.argv[1])\n"
          "assert z.testzip() is None\n"
          "for n in z.namelist(): xml.dom.minidom.parseString(z.read(n))\n"
          "d = xml.dom.minidom.parseString(z.read('3D/3dmodel.model'))\n"
          "assert len(d.getElementsByTagName('object')) == 1\n"
          "assert d.documentElement.getAttribute('unit') == 'millimeter'\n";
      write_file(dir.file("check.py"), script);
      CHECK(shell("/usr/bin/python3 " + shell_quote(dir.file("check.py")) + " " + shell_quote(path) + " >/dev/null 2>&1") == 0);
    }
  }

  SUBCASE("a copy re-compressed with deflate by python3's zipfile reads the same") {
    INFO("scripts/deps.sh installs python3");
    REQUIRE(have("/usr/bin/python3"));
    const std::string script =
        "import sys, zipfile\n"
        "src = zipfile.ZipFile(sys.argv[1])\n"
        "with zipfile.ZipFile(sys.argv[2], 'w', zipfile.ZIP_DEFLATED, compresslevel=9) as out:\n"
        "    for n in src.namelist(): out.writestr(n, src.read(n))\n";
    write_file(dir.file("deflate.py"), script);
    const std::string deflated = dir.file("deflated.3mf");
    REQUIRE(shell("/usr/bin/python3 " + shell_quote(dir.file("deflate.py")) + " " + shell_quote(path) + " " + shell_quote(deflated)) == 0);
    std::vector<ZipEntryInfo> entries;
    std::string error;
    REQUIRE(list_zip(read_file(deflated), entries, error));
    CHECK(entries[2].method == 8);
    CHECK(entries[2].compressed_size * 2 < entries[2].size);
    CHECK(identical(from_raw(read_raw_mesh(deflated)), solid));
  }
}

TEST_CASE("3MF: --unit is written as the model's unit, and a non-millimetre unit is read back with a warning") {
  const Mesh box = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 2, 3));
  for (const std::string& unit : units_3mf()) {
    CAPTURE(unit);
    const std::string bytes = write_3mf(box, unit);
    const RawMesh raw = read_raw_mesh_from_memory("box.3mf", bytes);
    CHECK(identical(from_raw(raw), box));
    if (unit == "millimeter") CHECK(raw.warnings.empty());
    else CHECK((raw.warnings.size() == 1 && raw.warnings[0].find("unit is " + unit) != std::string::npos));
  }
  CHECK_THROWS_AS(write_3mf(box, "furlong"), MeshInputError);
  Mesh bad = box;
  bad.V(0, 0) = std::nan("");
  CHECK_THROWS_AS(write_3mf(bad), MeshInputError);
}

TEST_CASE("3MF: build transforms and components are applied") {
  const Mesh box = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 2, 3));
  std::string verts, tris;
  for (Eigen::Index i = 0; i < box.V.rows(); ++i)
    verts += "<vertex x=\"" + number(box.V(i, 0)) + "\" y=\"" + number(box.V(i, 1)) + "\" z=\"" + number(box.V(i, 2)) + "\"/>";
  for (Eigen::Index f = 0; f < box.F.rows(); ++f)
    tris += "<triangle v1=\"" + std::to_string(box.F(f, 0)) + "\" v2=\"" + std::to_string(box.F(f, 1)) + "\" v3=\"" + std::to_string(box.F(f, 2)) + "\"/>";
  const std::string model =
      "<?xml version=\"1.0\"?>\n<model xmlns=\"http://schemas.microsoft.com/3dmanufacturing/core/2015/02\"><resources>"
      "<object id=\"3\"><mesh><vertices>" + verts + "</vertices><triangles>" + tris + "</triangles></mesh></object>"
      "<object id=\"4\"><components><component objectid=\"3\" transform=\"0 1 0 -1 0 0 0 0 1 0 0 0\"/>"
      "<component objectid=\"3\" transform=\"1 0 0 0 1 0 0 0 1 5 0 0\"/></components></object>"
      "<object id=\"5\" type=\"support\"><components><component objectid=\"3\"/></components></object>"
      "</resources><build><item objectid=\"4\" transform=\"2 0 0 0 2 0 0 0 2 0 0 1\"/><item objectid=\"5\"/></build></model>";
  const std::string bytes = write_zip({{"3D/3dmodel.model", model}});
  const RawMesh raw = read_raw_mesh_from_memory("t.3mf", bytes);
  REQUIRE(raw.V.rows() == 2 * box.V.rows());
  REQUIRE(raw.F.rows() == 2 * box.F.rows());
  // Vertex 6 of the box is (1, 2, 3): rotated by 90 degrees about z, (x, y) -> (-y, x), then scaled by 2, lifted by 1.
  const Eigen::Index k = 6;
  REQUIRE(box.V.row(k) == Eigen::RowVector3d(box.V(k, 0), box.V(k, 1), box.V(k, 2)));
  CHECK(raw.V(k, 0) == -2 * box.V(k, 1));
  CHECK(raw.V(k, 1) == 2 * box.V(k, 0));
  CHECK(raw.V(k, 2) == 2 * box.V(k, 2) + 1);
  CHECK(raw.V(box.V.rows() + k, 0) == 2 * (box.V(k, 0) + 5));
  REQUIRE(raw.warnings.size() == 1);
  CHECK(raw.warnings[0].find("support") != std::string::npos);
  // Two separate closed boxes, both facing out (the rotation keeps orientation).
  const LoadedMesh loaded = load_raw_mesh("t.3mf", raw);
  CHECK(loaded.components == 2);
}

TEST_CASE("3MF: hostile packages are refused with one printable line naming the file") {
  const auto refusal = [](const std::string& bytes) {
    try {
      read_raw_mesh_from_memory("h.3mf", bytes);
    } catch (const MeshInputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const auto printable = [](const std::string& message) {
    for (const char c : message)
      if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) return false;
    return message.rfind("h.3mf: ", 0) == 0;
  };
  const std::string head = "<model xmlns=\"http://schemas.microsoft.com/3dmanufacturing/core/2015/02\"><resources>";
  const std::string tail = "</resources><build><item objectid=\"1\"/></build></model>";
  struct Case {
    std::string bytes, expected;
  };
  // The model part, named with control bytes by the relationship, no longer matches its CRC.
  std::string crc = write_zip({{"_rels/.rels", "<Relationships><Relationship Type=\"http://schemas.microsoft.com/3dmanufacturing/"
                                               "2013/01/3dmodel\" Target=\"/\x01\x02name\x7f\"/></Relationships>"},
                               {"\x01\x02name\x7f", head + tail}});
  crc[crc.find("<resources>") + 1] ^= 1;
  // Components that double at every level: 2^25 instances from 25 objects, no vertex in any.
  std::string dag = head + "<object id=\"1\"><components><component objectid=\"2\"/><component objectid=\"2\"/></components></object>";
  for (int id = 2; id < 25; ++id)
    dag += "<object id=\"" + std::to_string(id) + "\"><components><component objectid=\"" + std::to_string(id + 1) +
           "\"/><component objectid=\"" + std::to_string(id + 1) + "\"/></components></object>";
  dag += "<object id=\"25\"><mesh><vertices/><triangles/></mesh></object>" + tail;
  std::string deep = head;
  for (int i = 0; i < 300; ++i) deep += "<x>";
  const Case cases[] = {
      {write_zip({{"3D/3dmodel.model", "<m\x80od" "\x01" "el/>"}}), "malformed XML"},
      {write_zip({{"3D/3dmodel.model", "<m\xc3\xa9" "del/>"}}), "the root element is <m\\xc3\\xa9del>"},
      {crc, "entry '\\x01\\x02name\\x7f': CRC-32 mismatch"},
      {write_zip({{"3D/3dmodel.model", dag}}), "more than 1048576 object instances"},
      {write_zip({{"3D/3dmodel.model", deep}}), "nested deeper than 256"},
      {write_zip({{"3D/3dmodel.model", head + "<object id=\"1\" id=\"2\"/>" + tail}}), "duplicate attribute 'id'"},
      {write_zip({{"3D/3dmodel.model", head + "<object id=\"1\"/><object id=\"1\"/>" + tail}}), "a second object with id 1"},
      {write_zip({{"3D/3dmodel.model", head + tail + "<model/>"}}), "a second root element"},
      {write_zip({{"3D/3dmodel.model", head + "<object id=\"1\"/>&bogus;" + tail}}), "unknown or malformed reference"},
      {write_zip({{"3D/3dmodel.model", head + "<object id=\"-1\"/>" + tail}}), "is not an index"},
      {write_zip({{"3D/3dmodel.model", head + "<object id=\"1\"><components><component objectid=\"1\" transform=\"1 0 0\"/></components></object>" + tail}}),
       "transform needs 12 numbers"},
      {write_zip({{"_rels/.rels", "<Relationships><Relationship Type=\"http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel\" Target=\"/a\x01" "b\"/></Relationships>"}}),
       "is not in the package"},
      {std::string("PK\x03\x04", 4) + std::string(40, '\0'), "not a zip archive"},
  };
  for (const Case& c : cases) {
    const std::string message = refusal(c.bytes);
    CAPTURE(message);
    CHECK(message.find(c.expected) != std::string::npos);
    CHECK(printable(message));
  }
  // The same model, well-formed, is accepted: the refusals above come from the defect alone.
  CHECK(refusal(write_zip({{"3D/3dmodel.model", head + "<object id=\"1\"><mesh><vertices/><triangles/></mesh></object>" + tail}})) == "accepted");
}
