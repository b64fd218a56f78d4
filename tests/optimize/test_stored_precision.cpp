// Verify the bytes written (issue 20): an STL output is verified as float32 reads it back. A CAD
// part written the way OpenSCAD writes a union (a plate whose top face is fanned from its corners
// to the footprint of a boss on it: long thin coplanar triangles that touch along edges), turned
// 0.6 rad about z so no x or y coordinate is a float32 number, is hollowed into STL files. The
// files read back are checked with code independent of the verifier (tests/mass/geometry_checks.h
// and tests/mesh_checks.h): the solid is closed and oriented, no two faces of it cross, no cavity
// face crosses the outer surface, and every cavity vertex keeps the requested wall from the
// outer surface, all on the float32 numbers of the file. A stepped block (a union of two boxes as
// OpenSCAD writes it: coplanar triangles touching along edges, concave creases) is read from an
// STL file itself and hollowed with and without --outer; the solid read back has no pair by the
// exact rule (geometry/mesh_defects.h, CGAL's semantics) nor by the test's own count.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "../mass/geometry_checks.h"
#include "../mesh_checks.h"
#include "../support.h"
#include "../temp_dir.h"
#include "geometry/mesh_defects.h"
#include "io/json.h"
#include "meshio/read_raw_mesh.h"
#include "meshio/write_mesh.h"
#include "util/det_math.h"

using namespace offsetopt;
using offsetopt::test::read_file;

namespace {

int add_vertex(Mesh& m, double x, double y, double z) {
  m.V.conservativeResize(m.V.rows() + 1, 3);
  m.V.row(m.V.rows() - 1) << x, y, z;
  return static_cast<int>(m.V.rows() - 1);
}

void add_face(Mesh& m, int a, int b, int c) {
  m.F.conservativeResize(m.F.rows() + 1, 3);
  m.F.row(m.F.rows() - 1) << a, b, c;
}

// A 40 x 40 x 2 plate with a boss of radius 6 and height 8 (n sides) at its centre, outward.
Mesh plate_with_boss(int n, double turn) {
  Mesh m{Vertices(0, 3), Faces(0, 3)};
  const double L = 40, h = 2, H = 10, r = 6, c = 20;
  int bottom[4], top[4];
  const double cx[4] = {0, L, L, 0}, cy[4] = {0, 0, L, L};
  for (int i = 0; i < 4; ++i) bottom[i] = add_vertex(m, cx[i], cy[i], 0);
  for (int i = 0; i < 4; ++i) top[i] = add_vertex(m, cx[i], cy[i], h);
  std::vector<int> ring(n), cap(n);
  for (int k = 0; k < n; ++k) {
    double s, co;
    det_sincos(2.0 * kPi * k / n, s, co);
    ring[k] = add_vertex(m, c + r * co, c + r * s, h);
    cap[k] = add_vertex(m, c + r * co, c + r * s, H);
  }
  add_face(m, bottom[0], bottom[2], bottom[1]);
  add_face(m, bottom[0], bottom[3], bottom[2]);
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    add_face(m, bottom[i], bottom[j], top[j]);
    add_face(m, bottom[i], top[j], top[i]);
  }
  // The plate's top: each ring edge fanned to the corner of its quadrant, and a corner-corner-ring
  // triangle where the quadrant changes (n a multiple of 4: ring vertex k·n/4 starts quadrant k).
  auto corner_of = [&](int k) { return top[(4 * k / n + 2) % 4]; };
  for (int k = 0; k < n; ++k) {
    const int next = (k + 1) % n;
    add_face(m, corner_of(k), ring[next], ring[k]);
    if (corner_of(next) != corner_of(k)) add_face(m, corner_of(k), corner_of(next), ring[next]);
  }
  const int centre = add_vertex(m, c, c, H);
  for (int k = 0; k < n; ++k) {
    const int next = (k + 1) % n;
    add_face(m, ring[k], ring[next], cap[next]);
    add_face(m, ring[k], cap[next], cap[k]);
    add_face(m, centre, cap[k], cap[next]);
  }
  double s, co;
  det_sincos(turn, s, co);
  for (Eigen::Index i = 0; i < m.V.rows(); ++i) {
    const double x = m.V(i, 0), y = m.V(i, 1);
    m.V(i, 0) = co * x - s * y;
    m.V(i, 1) = s * x + co * y;
  }
  return m;
}

Mesh read_back(const std::string& path) {
  const RawMesh raw = read_raw_mesh(path);
  return Mesh{raw.V, raw.F};
}

}  // namespace

TEST_CASE("a turned CAD part with coplanar touching faces, hollowed into STL, verifies on the float32 files") {
  const TempDir dir("offsetopt-stored-precision");
  const Mesh part = plate_with_boss(48, 0.6);
  REQUIRE(offsetopt::test::closed_and_oriented(part));
  const std::string input = dir.path() + "/part.ply", base = dir.path() + "/hollow";
  write_mesh(input, part);
  const int status = std::system(("timeout 300 " + std::string(OFFSETOPT_BINARY) + " optimize " + input +
                                  " --goal stand --quiet --no-timings -o " + base + ".stl --inner " + base +
                                  "_cavity.stl --outer-mesh " + base + "_outer.stl --report " + base + ".json 2>/dev/null")
                                     .c_str());
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 0);
  const Json report = Json::parse(read_file(base + ".json"));
  CHECK(report.at("after").at("rounded_for_output").at("precision").as_string() == "float32");
  CHECK(report.at("after").at("rounded_for_output").at("new_defects").as_number() == 0);

  const Mesh solid = read_back(base + ".stl"), outer = read_back(base + "_outer.stl"), cavity = read_back(base + "_cavity.stl");
  REQUIRE(cavity.F.rows() > 0);
  for (const Mesh* m : {&solid, &outer, &cavity})
    for (Eigen::Index i = 0; i < m->V.rows(); ++i)
      for (int c = 0; c < 3; ++c) REQUIRE(static_cast<double>(static_cast<float>(m->V(i, c))) == m->V(i, c));
  CHECK(solid.F.rows() == outer.F.rows() + cavity.F.rows());
  CHECK(offsetopt::test::closed_and_oriented(solid));
  CHECK(offsetopt::test::self_intersections(solid) == 0);
  CHECK(offsetopt::test::crossings_between(cavity, outer) == 0);
  const double wall = report.at("after").at("requested_wall").as_number();
  CHECK(offsetopt::test::min_vertex_distance(cavity, outer) >= wall);
}

namespace {

// A stepped block as OpenSCAD writes union() { cube([30, 20, 6]); translate([9, 0, 6])
// cube([12, 20, 10]); }: each side is one T-shaped polygon split into coplanar triangles that touch
// along edges (one a long sliver), and the base's top meets the step's walls at concave creases.
// Turned by `turn` about z and moved, so no x or y coordinate is a float32 number. 16 vertices:
// the basis is cut to 12 functions (--k 12).
Mesh stepped_block(double turn) {
  Mesh m{Vertices(0, 3), Faces(0, 3)};
  const double outline[8][2] = {{0, 0}, {30, 0}, {30, 6}, {21, 6}, {21, 16}, {9, 16}, {9, 6}, {0, 6}};  // (x, z)
  int a[8], b[8];  // the front (y = 0) and back (y = 20) polygons
  for (int i = 0; i < 8; ++i) a[i] = add_vertex(m, outline[i][0], 0, outline[i][1]);
  for (int i = 0; i < 8; ++i) b[i] = add_vertex(m, outline[i][0], 20, outline[i][1]);
  const int front[6][3] = {{0, 1, 2}, {0, 2, 3}, {0, 3, 6}, {0, 6, 7}, {6, 3, 4}, {6, 4, 5}};
  for (const auto& t : front) {
    add_face(m, a[t[0]], a[t[1]], a[t[2]]);
    add_face(m, b[t[0]], b[t[2]], b[t[1]]);
  }
  // The outline's edges joined front to back (quads a_i, a_j, b_j, b_i), outward.
  for (int i = 0; i < 8; ++i) {
    const int j = (i + 1) % 8;
    add_face(m, a[i], b[i], b[j]);
    add_face(m, a[i], b[j], a[j]);
  }
  double s, co;
  det_sincos(turn, s, co);
  for (Eigen::Index i = 0; i < m.V.rows(); ++i) {
    const double x = m.V(i, 0), y = m.V(i, 1);
    m.V(i, 0) = co * x - s * y + 12.345;
    m.V(i, 1) = s * x + co * y - 6.789;
  }
  return m;
}

}  // namespace

TEST_CASE("a stepped CAD block read from STL, hollowed with and without --outer into STL, verifies on the float32 file") {
  const TempDir dir("offsetopt-stl-round-trip");
  const std::string input = dir.path() + "/block.stl";
  write_mesh(input, stepped_block(0.6));
  const Mesh part = read_back(input);  // as the optimiser reads it: float32, points merged
  REQUIRE(part.V.rows() == 16);
  REQUIRE(offsetopt::test::closed_and_oriented(part));
  REQUIRE(find_self_intersections(part).pairs == 0);
  for (const std::string outer : {"", " --outer"}) {
    CAPTURE(outer);
    const std::string base = dir.path() + "/hollow" + (outer.empty() ? "" : "_outer");
    const int status = std::system(("timeout 300 " + std::string(OFFSETOPT_BINARY) + " optimize " + input + outer +
                                    " --goal stand --k 12 --quiet --no-timings -o " + base + ".stl --report " + base +
                                    ".json 2>/dev/null")
                                       .c_str());
    REQUIRE(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 0);
    const Json report = Json::parse(read_file(base + ".json"));
    CHECK(report.at("after").at("rounded_for_output").at("new_defects").as_number() == 0);
    if (!outer.empty()) CHECK(report.at("after").at("outer_new_self_intersections").as_number() == 0);
    // The solid as it reads back: float32 numbers, closed and oriented, and no two faces
    // intersecting by the exact rule (CGAL's, geometry/faces_intersect_exact.h) nor crossing by
    // the test's own floating-point count.
    const Mesh solid = read_back(base + ".stl");
    REQUIRE(solid.F.rows() > part.F.rows());
    for (Eigen::Index i = 0; i < solid.V.rows(); ++i)
      for (int c = 0; c < 3; ++c) REQUIRE(static_cast<double>(static_cast<float>(solid.V(i, c))) == solid.V(i, c));
    CHECK(offsetopt::test::closed_and_oriented(solid));
    const SelfIntersectionReport exact = find_self_intersections(solid);
    CHECK(exact.pairs == 0);
    CHECK(exact.collinear_faces == 0);
    CHECK(offsetopt::test::self_intersections(solid) == 0);
  }
}
