// Real-world inputs (issue 13): CAD zero-area slivers accepted with exact mass properties, OBJ
// corner dialects and polygons of any corner count (ear clipping in the polygon's plane), and
// the geometric defects `check` refuses and the other commands accept with a warning:
// self-intersecting face pairs and pinches. Expected pairs come from an independent brute-force
// search with the project's existing pair rule (geometry/intersecting_faces.h).
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "geometry/bvh.h"
#include "geometry/intersecting_faces.h"
#include "geometry/mesh_defects.h"
#include "mass/mass_properties.h"
#include "mesh/primitives.h"
#include "meshio/load_mesh.h"
#include "meshio/read_obj.h"
#include "meshio/triangulate_obj_face.h"
#include "meshio/validate_mesh.h"
#include "meshio_test_util.h"
#include "sliver_box.h"
#include "util/det_math.h"

using namespace offsetopt;
using namespace meshio_test;

namespace {

const TempDir& scratch() {
  static const TempDir dir("offsetopt_real_inputs");
  return dir;
}

// OBJ text of a mesh; `corner` formats one 1-based vertex index as a face corner.
std::string obj_text(const Mesh& m, const std::string& header = "",
                     std::string (*corner)(int) = [](int i) { return std::to_string(i); }) {
  std::string out = header;
  for (Eigen::Index i = 0; i < m.V.rows(); ++i)
    out += "v " + number(m.V(i, 0)) + " " + number(m.V(i, 1)) + " " + number(m.V(i, 2)) + "\n";
  for (Eigen::Index f = 0; f < m.F.rows(); ++f)
    out += "f " + corner(m.F(f, 0) + 1) + " " + corner(m.F(f, 1) + 1) + " " + corner(m.F(f, 2) + 1) + "\n";
  return out;
}

std::string write_obj(const std::string& name, const std::string& text) {
  const std::string path = scratch().file(name);
  write_file(path, text);
  return path;
}

double max_abs_difference(const Vector10d& a, const Vector10d& b) { return (a - b).cwiseAbs().maxCoeff(); }

// The smallest intersecting pair by brute force over all face pairs, with the existing rule of
// geometry/intersecting_faces.h (faces share corners by index), and the number of pairs.
std::pair<std::pair<int, int>, long long> brute_force_pairs(const Mesh& m) {
  const TriangleBvh bvh(m.V, m.F);
  std::pair<int, int> first{-1, -1};
  long long count = 0;
  for (int f = 0; f < m.F.rows(); ++f)
    for (int g = f + 1; g < m.F.rows(); ++g)
      if (mesh_faces_intersect(bvh, f, g)) {
        if (count++ == 0) first = {f, g};
      }
  return {first, count};
}

// An icosphere whose north pole is pushed down through the south side: a closed, consistently
// oriented surface whose pole faces cross the faces around the south pole.
Mesh folded_shell() {
  Mesh m = make_icosphere(1.0, 1);
  Eigen::Index top = 0;
  for (Eigen::Index i = 1; i < m.V.rows(); ++i)
    if (m.V(i, 2) > m.V(top, 2)) top = i;
  m.V.row(top) << 0.013, 0.021, -1.6;
  return m;
}

// Two boxes touching at one corner, (1, 1, 1), written with two distinct vertex indices there.
Mesh pinched_pair() {
  const Mesh a = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1));
  const Mesh b = make_box(Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(2, 3, 2));
  Mesh m;
  m.V.resize(16, 3);
  m.V << a.V, b.V;
  m.F.resize(24, 3);
  m.F << a.F, b.F.array() + 8;
  return m;
}

// Crossing-number test in the xy plane (the point is never on the outline in these tests).
bool inside_polygon(const std::vector<Eigen::Vector3d>& p, const Eigen::Vector3d& q) {
  bool inside = false;
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++)
    if ((p[i].y() > q.y()) != (p[j].y() > q.y()) &&
        q.x() < (p[j].x() - p[i].x()) * (q.y() - p[i].y()) / (p[j].y() - p[i].y()) + p[i].x())
      inside = !inside;
  return inside;
}

// The triangulation covers the polygon exactly: every triangle counter-clockwise with its
// centroid inside, and the areas summing to the polygon's analytic area.
void check_triangulation(const std::vector<Eigen::Vector3d>& polygon, double analytic_area) {
  std::vector<int> triangles;
  long long budget = 1000000;
  const PolygonTriangulationStatus how = triangulate_obj_face(polygon, triangles, budget);
  CHECK(how == PolygonTriangulationStatus::ear_clipping);
  REQUIRE(triangles.size() == 3 * (polygon.size() - 2));
  double sum = 0;
  for (std::size_t t = 0; t < triangles.size(); t += 3) {
    const Eigen::Vector3d a = polygon[static_cast<std::size_t>(triangles[t])], b = polygon[static_cast<std::size_t>(triangles[t + 1])],
                          c = polygon[static_cast<std::size_t>(triangles[t + 2])];
    const double area = 0.5 * (b - a).cross(c - a).z();
    CHECK(area > 0.0);
    CHECK(inside_polygon(polygon, (a + b + c) / 3.0));
    sum += area;
  }
  CHECK(std::fabs(sum - analytic_area) <= 1e-12 * analytic_area);
}

// A prism over the polygon `base` (counter-clockwise in xy) from z = 0 to z = height, the caps
// written as two polygons and the sides as quads.
std::string prism_obj(const std::vector<Eigen::Vector3d>& base, double height) {
  const std::size_t n = base.size();
  std::string out;
  for (double z : {0.0, height})
    for (const auto& p : base) out += "v " + number(p.x()) + " " + number(p.y()) + " " + number(z) + "\n";
  out += "f";
  for (std::size_t i = n; i-- > 0;) out += " " + std::to_string(i + 1);  // bottom, seen from below
  out += "\nf";
  for (std::size_t i = 0; i < n; ++i) out += " " + std::to_string(n + i + 1);
  out += "\n";
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    out += "f " + std::to_string(i + 1) + " " + std::to_string(j + 1) + " " + std::to_string(n + j + 1) + " " +
           std::to_string(n + i + 1) + "\n";
  }
  return out;
}

}  // namespace

TEST_CASE("zero-area slivers with distinct corners: valid, counted, and exactly the clean box's mass properties") {
  const Mesh box = sliver_test::sliver_box();
  const Mesh clean = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 4, 6));
  const MeshValidation v = validate_mesh(box);
  CHECK(v.valid());
  CHECK(v.zero_area_faces == 2);
  CHECK(v.first_zero_area_face == 13);  // the first sliver: face 0 split, 12 = (m, b, c), 13 = (a, b, m)
  CHECK(v.genus == 0);

  const Vector10d p = mass_properties(box), q = mass_properties(clean);
  CHECK(q(0) == doctest::Approx(48.0));
  CHECK(max_abs_difference(p, q) <= 1e-12 * q.cwiseAbs().maxCoeff());

  const LoadedMesh loaded = load_raw_mesh("slivers.obj", RawMesh{MeshFormat::obj, box.V, box.F, {}, {}, {}});
  REQUIRE(loaded.warnings.size() == 1);
  CHECK(loaded.warnings[0].find("2 zero-area faces with three distinct collinear corners (first: face 13)") == 0);
  CHECK(loaded.mesh.F.rows() == box.F.rows());  // nothing dropped or flipped

  // The T-junctions are not self-intersections, and nothing is pinched.
  CHECK(find_self_intersections(box).pairs == 0);
  CHECK(find_pinches(box).pairs == 0);

  const std::string path = write_obj("slivers.obj", obj_text(box));
  const RunResult r = run_offsetopt("check " + shell_quote(path), scratch());
  CHECK(r.exit_code == 0);
  CHECK(r.err.find("Warning: " + path + ": 2 zero-area faces") != std::string::npos);
  CHECK(r.out.find(": ok:") != std::string::npos);
}

TEST_CASE("OBJ corner dialects v, v/vt, v/vt/, v//, v//vn, v/vt/vn read the same mesh") {
  const Mesh box = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 2, 3));
  const std::string header = "vt 0 0\nvt 1 0\nvn 0 0 1\n";
  using Corner = std::string (*)(int);
  const std::vector<std::pair<std::string, Corner>> dialects = {
      {"v", [](int i) { return std::to_string(i); }},
      {"v/vt", [](int i) { return std::to_string(i) + "/1"; }},
      {"v/vt/", [](int i) { return std::to_string(i) + "/2/"; }},
      {"v//", [](int i) { return std::to_string(i) + "//"; }},
      {"v//vn", [](int i) { return std::to_string(i) + "//1"; }},
      {"v/vt/vn", [](int i) { return std::to_string(i) + "/1/1"; }},
      {"negative v/vt/", [](int i) { return std::to_string(i - 9) + "/-1/"; }},
  };
  for (const auto& [name, corner] : dialects) {
    CAPTURE(name);
    const RawMesh raw = read_obj("cube.obj", obj_text(box, header, corner));
    CHECK(identical(Mesh{raw.V, raw.F}, box));
  }
  // Real errors keep their file and line.
  CHECK_THROWS_WITH_AS(read_obj("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/x/ 2 3\n"),
                       "bad.obj:4: face corner '1/x/' is not an index (v, v/vt, v/vt/, v//, v//vn or v/vt/vn)", MeshInputError);
  CHECK_THROWS_WITH_AS(read_obj("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1/1/1 2 3\n"),
                       "bad.obj:4: face corner '1/1/1/1' has more than three parts", MeshInputError);
  CHECK_THROWS_WITH_AS(read_obj("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//0 2 3\n"),
                       "bad.obj:4: index 0 in face corner '1//0' (OBJ counts from 1)", MeshInputError);
}

TEST_CASE("a 300-corner prism: caps of 300 corners read whole, closed, with the analytic volume") {
  const int n = 300;
  const double radius = 2.5, height = 1.75;
  std::vector<Eigen::Vector3d> base;
  for (int i = 0; i < n; ++i) {
    double s, c;
    det_sincos(2.0 * kPi * i / n, s, c);
    base.emplace_back(radius * c, radius * s, 0.0);
  }
  const std::string path = write_obj("prism300.obj", prism_obj(base, height));
  const LoadedMesh loaded = load_mesh(path);
  CHECK(loaded.mesh.F.rows() == 2 * (n - 2) + 2 * n);
  double s, c;
  det_sincos(2.0 * kPi / n, s, c);
  const double analytic = 0.5 * n * radius * radius * s * height;
  CHECK(std::fabs(mass_properties(loaded.mesh)(0) - analytic) <= 1e-12 * analytic);
  const RunResult r = run_offsetopt("check " + shell_quote(path), scratch());
  CHECK(r.exit_code == 0);
}

TEST_CASE("non-convex polygons are ear-clipped inside their outline: an L, a star, and an L-shaped prism") {
  // L: the 3 x 3 square without its upper-right 2 x 2 square; area 5.
  const std::vector<Eigen::Vector3d> ell = {{0, 0, 0}, {3, 0, 0}, {3, 1, 0}, {1, 1, 0}, {1, 3, 0}, {0, 3, 0}};
  check_triangulation(ell, 5.0);
  // Rotated so that corner 0 is the reflex one (a fan from it would leave the outline).
  check_triangulation({{1, 1, 0}, {1, 3, 0}, {0, 3, 0}, {0, 0, 0}, {3, 0, 0}, {3, 1, 0}}, 5.0);
  // Five-pointed star, outer radius 2, inner 0.8: area = 5 R r sin(36 deg).
  std::vector<Eigen::Vector3d> star;
  for (int i = 0; i < 10; ++i) {
    double s, c;
    det_sincos(kPi / 2 + kPi * i / 5, s, c);
    const double r = i % 2 == 0 ? 2.0 : 0.8;
    star.emplace_back(r * c, r * s, 0.0);
  }
  double s36, c36;
  det_sincos(kPi / 5, s36, c36);
  check_triangulation(star, 5 * 2.0 * 0.8 * s36);

  // The same outline as a polygon in a tilted plane triangulates to the same area (Newell normal).
  const std::string path = write_obj("ell_prism.obj", prism_obj({{1, 1, 0}, {1, 3, 0}, {0, 3, 0}, {0, 0, 0}, {3, 0, 0}, {3, 1, 0}}, 2.0));
  const LoadedMesh loaded = load_mesh(path);
  CHECK(std::fabs(mass_properties(loaded.mesh)(0) - 10.0) <= 1e-12 * 10.0);
  bool warned = false;
  for (const auto& w : loaded.warnings) warned = warned || w.find("2 non-convex polygons triangulated by ear clipping") == 0;
  CHECK(warned);
  CHECK(run_offsetopt("check " + shell_quote(path), scratch()).exit_code == 0);
}

TEST_CASE("ear clipping: clockwise outlines keep their orientation, convex ones are fanned, the work cap is reported") {
  // The L clockwise seen from +z: Newell's normal points down, every triangle must too.
  std::vector<Eigen::Vector3d> ell = {{0, 3, 0}, {1, 3, 0}, {1, 1, 0}, {3, 1, 0}, {3, 0, 0}, {0, 0, 0}};
  std::vector<int> triangles;
  long long budget = 1000000;
  REQUIRE(triangulate_obj_face(ell, triangles, budget) == PolygonTriangulationStatus::ear_clipping);
  double area = 0;
  for (std::size_t t = 0; t < triangles.size(); t += 3) {
    const double z = (ell[static_cast<std::size_t>(triangles[t + 1])] - ell[static_cast<std::size_t>(triangles[t])])
                         .cross(ell[static_cast<std::size_t>(triangles[t + 2])] - ell[static_cast<std::size_t>(triangles[t])])
                         .z();
    CHECK(z < 0.0);
    area -= 0.5 * z;
  }
  CHECK(area == doctest::Approx(5.0).epsilon(1e-15));
  // A convex hexagon: the fan from corner 0, as the other readers triangulate.
  const std::vector<Eigen::Vector3d> hexagon = {{2, 0, 1}, {1, 2, 1}, {-1, 2, 1}, {-2, 0, 1}, {-1, -2, 1}, {1, -2, 1}};
  REQUIRE(triangulate_obj_face(hexagon, triangles, budget) == PolygonTriangulationStatus::fan);
  CHECK(triangles == std::vector<int>{0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 5});
  // A comb of 400 teeth with a budget of 1000 point tests runs out and returns no triangles.
  std::vector<Eigen::Vector3d> comb = {{0, -1, 0}};
  for (int i = 0; i < 400; ++i) {
    comb.emplace_back(2 * i + 1, 0, 0);
    comb.emplace_back(2 * i + 1.5, 5, 0);
    comb.emplace_back(2 * i + 2, 0, 0);
  }
  comb.emplace_back(801, -1, 0);
  budget = 1000;
  CHECK(triangulate_obj_face(comb, triangles, budget) == PolygonTriangulationStatus::budget_exhausted);
  CHECK(triangles.empty());
  budget = 100000000;
  REQUIRE(triangulate_obj_face(comb, triangles, budget) == PolygonTriangulationStatus::ear_clipping);
  CHECK(triangles.size() == 3 * (comb.size() - 2));
}

TEST_CASE("a folded shell: check names the first self-intersecting pair, inspect accepts it with a warning") {
  const Mesh m = folded_shell();
  REQUIRE(validate_mesh(m).valid());
  const auto [first, count] = brute_force_pairs(m);
  REQUIRE(count > 0);
  const SelfIntersectionReport report = find_self_intersections(m);
  CHECK(report.pairs == count);
  CHECK(report.first_face == first.first);
  CHECK(report.second_face == first.second);
  CHECK_FALSE(report.truncated);
  CHECK(find_self_intersections(m, 1).truncated);

  const std::string path = write_obj("folded.obj", obj_text(m));
  const std::string pair = "(first: faces " + std::to_string(first.first) + " and " + std::to_string(first.second) +
                           ", lines " + std::to_string(m.V.rows() + first.first + 1) + " and " +
                           std::to_string(m.V.rows() + first.second + 1);
  const RunResult check = run_offsetopt("check " + shell_quote(path), scratch());
  CHECK(check.exit_code == 2);
  CHECK(check.err.find("Error: " + path + ": " + std::to_string(count) + " self-intersecting face pairs " + pair) !=
        std::string::npos);
  const RunResult inspect = run_offsetopt("inspect " + shell_quote(path), scratch());
  CHECK(inspect.exit_code == 0);
  CHECK(inspect.err.find("Warning: " + std::to_string(count) + " self-intersecting face pairs " + pair) != std::string::npos);
}

TEST_CASE("a pinched pair: check names the two vertices at one position, inspect accepts it with a warning") {
  const Mesh m = pinched_pair();
  const PinchReport report = find_pinches(m);
  CHECK(report.pairs == 1);
  CHECK(report.first_vertex == 7);   // (1, 1, 1), the first box's top corner
  CHECK(report.second_vertex == 8);  // the second box's bottom corner
  CHECK(find_self_intersections(m).pairs == 0);  // touching at the pinch is not a crossing

  const std::string path = write_obj("pinched.obj", obj_text(m));
  const RunResult check = run_offsetopt("check " + shell_quote(path), scratch());
  CHECK(check.exit_code == 2);
  CHECK(check.err.find("Error: " + path + ": 1 pinch: distinct vertices at one position whose fans touch only there "
                       "(first: vertices 7 and 8, lines 8 and 9") != std::string::npos);
  const RunResult inspect = run_offsetopt("inspect " + shell_quote(path), scratch());
  CHECK(inspect.exit_code == 0);
  CHECK(inspect.err.find("Warning: 1 pinch: distinct vertices at one position whose fans touch only there (first: vertices 7 and 8") !=
        std::string::npos);
}

TEST_CASE("the demo meshes have no self-intersecting pairs and no pinches") {
  const std::filesystem::path folder = std::filesystem::path(OFFSETOPT_SOURCE_DIR) / "meshes";
  int meshes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.path().extension() != ".obj") continue;
    CAPTURE(entry.path().string());
    const LoadedMesh loaded = load_mesh(entry.path().string());
    CHECK(find_self_intersections(loaded.mesh).pairs == 0);
    CHECK(find_pinches(loaded.mesh).pairs == 0);
    ++meshes;
  }
  CHECK(meshes >= 8);
}

TEST_CASE("optimize --goal stand on a gridded box with slivers and needles exits 0 and verifies") {
  Mesh m = sliver_test::grid_box(2, 2, 4, 4);  // 0.25 grid: 2 x 2 x 4 box
  const Mesh clean = m;
  const Eigen::Index faces = m.F.rows();
  for (int k = 0; k < 6; ++k) sliver_test::add_sliver(m, static_cast<int>(k * faces / 6 + 5));
  sliver_test::add_fan_point(m, 3, 1e-7, 1e-7);
  sliver_test::add_fan_point(m, static_cast<int>(faces / 2 + 1), 0.5, 1e-9);
  const MeshValidation v = validate_mesh(m);
  REQUIRE(v.valid());
  CHECK(v.zero_area_faces == 6);
  const Vector10d p = mass_properties(m), q = mass_properties(clean);
  CHECK(q(0) == doctest::Approx(16.0));
  CHECK(max_abs_difference(p, q) <= 1e-12 * q.cwiseAbs().maxCoeff());
  CHECK(find_self_intersections(m).pairs == 0);

  const std::string path = write_obj("grid_slivers.obj", obj_text(m)), out = scratch().file("grid_slivers_out.obj");
  const std::string command = "timeout 300 " + shell_quote(OFFSETOPT_BINARY) + " optimize " + shell_quote(path) +
                              " --goal stand --quiet -o " + shell_quote(out) + " 2>" + shell_quote(scratch().file("optimize_err.txt"));
  const int status = std::system(command.c_str());
  REQUIRE(status != -1);
  CHECK(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 0);
  INFO(read_file(scratch().file("optimize_err.txt")));
  // The written solid (outer surface and cavity, two shells) loads as a valid solid, and no face
  // of it crosses another (the cavity stays inside, slivers or not).
  const LoadedMesh solid = load_mesh(out);
  CHECK(solid.components == 2);
  CHECK(find_self_intersections(solid.mesh).pairs == 0);
  CHECK(mass_properties(solid.mesh)(0) < 16.0);
}
