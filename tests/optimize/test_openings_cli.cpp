// Openings through the written cavity (issue 20), end to end on the demo bottle and sphere, checked on the
// files as they read back with code independent of the verifier (tests/mesh_checks.h,
// tests/mass/geometry_checks.h): the solid is one closed, oriented piece, no two faces cross, the
// void is one region joined to the outside (a 6-connected flood fill from the grid's border over
// cells whose centres are outside the material), every vertex off the outer surface and off the
// opening's own surface keeps the requested wall, and the report's figures meet the goal.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../mass/geometry_checks.h"
#include "../mesh_checks.h"
#include "../outside_cells.h"
#include "../solid_checks.h"
#include "../temp_dir.h"
#include "geometry/bvh.h"
#include "geometry/mesh_shells.h"
#include "geometry/point_in_solid.h"
#include "io/json.h"
#include "meshio/read_raw_mesh.h"

using namespace offsetopt;

namespace {

const std::string kMeshes = std::string(OFFSETOPT_SOURCE_DIR) + "/meshes/";

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

Mesh read_back(const std::string& path) {
  const RawMesh raw = read_raw_mesh(path);
  return Mesh{raw.V, raw.F};
}

int run(const std::string& arguments) {
  const int status = std::system(("timeout 900 " + std::string(OFFSETOPT_BINARY) + " optimize " + arguments + " --quiet --no-timings 2>/dev/null").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Cells of spacing h outside `solid` that the flood fill from the border does not reach.
long long enclosed_void_cells(const Mesh& solid, double h) {
  const test::OutsideCells cells = test::outside_cells(solid, h);
  long long enclosed = 0;
  for (std::size_t i = 0; i < cells.material.size(); ++i) enclosed += !cells.material[i] && !cells.outside[i] ? 1 : 0;
  return enclosed;
}

// The solid as printed with its openings: closed and oriented, no two faces crossing, and no void
// cell (of side h: 2 mm unless the void has passages thinner than that) the outside does not reach.
void check_open_solid(const Mesh& solid, double h = 2.0) {
  CHECK(test::closed_and_oriented(solid));
  CHECK(test::self_intersections(solid) == 0);
  CHECK(enclosed_void_cells(solid, h) == 0);
}

// The smallest distance to `outer` over the vertices of `solid` that are not on it (farther than
// `on`) and not on an opening's side (radius r around its axis, between its caps).
double wall_off_openings(const Mesh& solid, const Mesh& outer, const Json& cut, double on) {
  Mesh kept{Vertices(0, 3), Faces(0, 3)};
  std::vector<Eigen::Vector3d> points;
  for (Eigen::Index v = 0; v < solid.V.rows(); ++v) {
    const Eigen::Vector3d p = solid.V.row(v).transpose();
    bool exempt = false;
    for (std::size_t i = 0; i < cut.size(); ++i) {
      const Json& c = cut.at(i);
      const Eigen::Vector3d a(c.at("inner").at(0).as_number(), c.at("inner").at(1).as_number(), c.at("inner").at(2).as_number());
      const Eigen::Vector3d b(c.at("outer").at(0).as_number(), c.at("outer").at(1).as_number(), c.at("outer").at(2).as_number());
      const double r = c.at("radius").as_number();
      const Eigen::Vector3d axis = (b - a).normalized();
      const double along = (p - a).dot(axis);
      const double radial = ((p - a) - along * axis).norm();
      exempt = exempt || (along >= -1e-6 * r && along <= (b - a).norm() + 1e-6 * r && radial >= 0.99 * r && radial <= 1.000001 * r);
    }
    if (!exempt) points.push_back(p);
  }
  kept.V.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) kept.V.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  double best = std::numeric_limits<double>::infinity();
  for (Eigen::Index v = 0; v < kept.V.rows(); ++v) {
    Mesh one{kept.V.row(v), Faces(0, 3)};
    const double d = test::min_vertex_distance(one, outer);
    if (d > on) best = std::min(best, d);
  }
  return best;
}

}  // namespace

TEST_CASE("drain holes auto on the bottle: one piece, the void open to the outside, the wall kept") {
  const TempDir dir("offsetopt-drain-holes");
  const std::string base = dir.path() + "/bottle";
  REQUIRE(run(kMeshes + "bottle.obj --goal stand --drain-holes auto --drain-hole-radius 5 -o " + base + ".stl --outer-mesh " + base +
              "_outer.stl --report " + base + ".json") == 0);
  const Json report = Json::parse(read_file(base + ".json"));
  const Json& cut = report.at("openings").at("cut");
  REQUIRE(cut.size() == report.at("openings").at("cavity_shells").as_number());
  const Mesh solid = read_back(base + ".stl"), outer = read_back(base + "_outer.stl");
  check_open_solid(solid);
  CHECK(mesh_shells(solid, Eigen::Vector3d(40, 0, 100)).count == 1);
  const double wall = report.at("after").at("requested_wall").as_number();
  CHECK(wall_off_openings(solid, outer, cut, 1e-6 * wall) >= wall * (1.0 - 1e-6));
}

TEST_CASE("the demo bottle as a container: stand-filled --outer with an opening in the neck") {
  const TempDir dir("offsetopt-container");
  const std::string base = dir.path() + "/bottle";
  REQUIRE(run(kMeshes + "bottle.obj --goal stand-filled --fill-density 0.8 --outer --fix 'z>238' -o " + base + ".stl --outer-mesh " +
              base + "_outer.stl --report " + base + ".json") == 0);
  const Json report = Json::parse(read_file(base + ".json"));
  const Json& openings = report.at("openings");
  REQUIRE(openings.at("cut").size() == 1);
  CHECK(openings.at("cut").at(0).at("kind").as_string() == "channel");
  CHECK(openings.contains("liquid_volume"));
  const double margin = report.at("parameters").at("margin").as_number();
  CHECK(report.at("after").at("empty").at("com_margin").as_number() >= margin);
  CHECK(report.at("after").at("filled").at("com_margin").as_number() >= margin);
  const Mesh solid = read_back(base + ".stl"), outer = read_back(base + "_outer.stl");
  check_open_solid(solid);
  CHECK(mesh_shells(solid, Eigen::Vector3d(40, 0, 100)).count == 1);
  const double wall = report.at("after").at("requested_wall").as_number();
  CHECK(wall_off_openings(solid, outer, openings.at("cut"), 1e-6 * wall) >= wall * (1.0 - 1e-6));
}

TEST_CASE("the demo bottle as a container with a sphere region: a hole at the neck's top, in the region") {
  // --fix sphere: about the middle of the neck's top face (z = 245): refused before (a contoured
  // cavity could only be opened for a half-space). The hole's mouth lies inside the region, the
  // liquid spills at its lowest point, both stand checks hold, and the walls away from it are kept.
  const TempDir dir("offsetopt-container-sphere");
  const std::string base = dir.path() + "/bottle";
  REQUIRE(run(kMeshes + "bottle.obj --goal stand-filled --fill-density 0.8 --outer --fix sphere:110.25,0,245,8 -o " + base +
              ".stl --outer-mesh " + base + "_outer.stl --report " + base + ".json") == 0);
  const Json report = Json::parse(read_file(base + ".json"));
  const Json& openings = report.at("openings");
  REQUIRE(openings.at("cut").size() == 1);
  const Json& hole = openings.at("cut").at(0);
  CHECK(hole.at("kind").as_string() == "opening");
  const double wall = report.at("after").at("requested_wall").as_number();
  const double radius = hole.at("radius").as_number();
  const Eigen::Vector3d mouth(hole.at("outer").at(0).as_number(), hole.at("outer").at(1).as_number(),
                              hole.at("outer").at(2).as_number());
  const Eigen::Vector3d inner(hole.at("inner").at(0).as_number(), hole.at("inner").at(1).as_number(),
                              hole.at("inner").at(2).as_number());
  // The outer cap is radius + 2 walls beyond the surface: the surface point is that far back.
  const Eigen::Vector3d on_surface = mouth - (radius + 2.0 * wall) * (mouth - inner).normalized();
  CHECK((on_surface - Eigen::Vector3d(110.25, 0, 245)).norm() + radius <= 8.0);
  CHECK(openings.contains("liquid_volume"));
  const double margin = report.at("parameters").at("margin").as_number();
  CHECK(report.at("after").at("empty").at("com_margin").as_number() >= margin);
  CHECK(report.at("after").at("filled").at("com_margin").as_number() >= margin);
  const Mesh solid = read_back(base + ".stl"), outer = read_back(base + "_outer.stl");
  // 1 mm: at 2 mm one cell of the base's thin void (z = 23) has every neighbour's centre in the
  // material.
  check_open_solid(solid, 1.0);
  CHECK(mesh_shells(solid, Eigen::Vector3d(40, 0, 100)).count == 1);
  CHECK(wall_off_openings(solid, outer, openings.at("cut"), 1e-6 * wall) >= wall * (1.0 - 1e-6));
}

TEST_CASE("a small volume with a drain hole: the ball is aimed lower by what the hole's channel holds") {
  // The demo sphere's offset void cannot hold 1000, the ball clipped to the carvable cells can;
  // the drain hole's channel to the outside is part of the void (about 300), so the ball is aimed
  // lower until the opened void holds the target. Measured on the files: the void is the outer
  // surface's volume less the solid's, and open to the outside.
  const TempDir dir("offsetopt-small-volume-hole");
  const std::string base = dir.path() + "/sphere";
  REQUIRE(run(kMeshes + "sphere.obj --goal volume --target-volume 1000 --drain-holes auto -o " + base + ".stl --outer-mesh " +
              base + "_outer.stl --report " + base + ".json") == 0);
  const Json report = Json::parse(read_file(base + ".json"));
  CHECK(report.at("cavity").at("written").as_string() == "quadric");
  const Mesh solid = read_back(base + ".stl"), outer = read_back(base + "_outer.stl");
  check_open_solid(solid);
  const Eigen::Vector3d origin = outer.V.colwise().mean().transpose();
  const double held = test::integrals_of(outer, origin).volume - test::integrals_of(solid, origin).volume;
  CHECK(std::fabs(held - 1000.0) <= 1e-4 * 1000.0);
  // Aimed at 1000 itself, the opened void held over a quarter more.
  CHECK(report.at("openings").at("rounds").as_number() >= 2);
}

TEST_CASE("a volume through a half-space opening: the ball under the opening, aimed lower by what the channel holds") {
  // The demo sphere (centre z = 30, radius 30). With the ball at the middle, the channel through
  // z>55 alone held 1587 of a target of 1000, and the one through z>5 lengthened as the ball shrank
  // (20000 took four aims, more than the three allowed): both exited 3. The ball now starts on the
  // channel's axis under the opening; measured on the files, the void holds the target and is open.
  // Through z>5 at 300 the channel holds a sixth of the void: aimed by a secant on what the
  // opened void held, and each aimed void checked to the target's own 1e-4, it took seven rounds.
  for (const auto& [region, target] :
       {std::pair<std::string, double>{"z>55", 1000.0}, {"z>5", 20000.0}, {"z>5", 300.0}}) {
    CAPTURE(region);
    const TempDir dir("offsetopt-volume-channel");
    const std::string base = dir.path() + "/sphere";
    REQUIRE(run(kMeshes + "sphere.obj --goal volume --target-volume " + std::to_string(target) + " --fix '" + region + "' -o " +
                base + ".stl --outer-mesh " + base + "_outer.stl --report " + base + ".json") == 0);
    const Json report = Json::parse(read_file(base + ".json"));
    CHECK(report.at("cavity").at("written").as_string() == "quadric");
    const Json& channel = report.at("openings").at("cut").at(0);
    CHECK(channel.at("kind").as_string() == "channel");
    // Its inner end, inside the void, is above the top of a ball of that volume at the middle
    // (z = 36.2 and 46.8): the ball is under the opening.
    CHECK(channel.at("inner").at(2).as_number() > 30.0 + std::cbrt(3.0 * target / (4.0 * 3.141592653589793)));
    const Mesh solid = read_back(base + ".stl"), outer = read_back(base + "_outer.stl");
    check_open_solid(solid);
    const Eigen::Vector3d origin = outer.V.colwise().mean().transpose();
    const double held = test::integrals_of(outer, origin).volume - test::integrals_of(solid, origin).volume;
    CHECK(std::fabs(held - target) <= 1e-4 * target);
    CHECK(report.at("openings").at("rounds").as_number() <= 4);
  }
}
