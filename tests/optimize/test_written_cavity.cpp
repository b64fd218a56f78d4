// The contoured cavity and its moment-space correction on the demo goals, checked on the files
// written, with code independent of the tool's own verification: the cavity file's shells are
// closed and consistently oriented, no face of it meets another or the outer surface, every
// cavity vertex keeps the requested wall from the outer surface (closest point over every outer
// face), and the goal holds for the mass properties of the written solid (outer less cavity).
// Also two real meshes of ../shared/realposed (skipped without it) that some void reaches and the
// tool once refused as its own shortfall.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "../mass/geometry_checks.h"
#include "../mesh_checks.h"
#include "../solid_checks.h"
#include "../support.h"
#include "../temp_dir.h"
#include "io/json.h"
#include "meshio/read_raw_mesh.h"
#include "util/format_double.h"

using namespace offsetopt;
using offsetopt::test::closed_and_oriented;
using offsetopt::test::read_file;

namespace {

const std::string kBinary = OFFSETOPT_BINARY;
const std::string kMeshes = std::string(OFFSETOPT_SOURCE_DIR) + "/meshes/";

const std::string& temp_dir() {
  static const TempDir dir("offsetopt-cavity");
  return dir.path();
}

Mesh read_mesh(const std::string& path) {
  const RawMesh raw = read_raw_mesh(path);
  return Mesh{raw.V, raw.F};
}

struct Written {
  int exit_code = -1;
  Json report;
  Mesh outer, cavity;
};

// `mesh`: a path, or a name in meshes/.
Written optimize(const std::string& name, const std::string& mesh, const std::string& options) {
  const std::string base = temp_dir() + "/" + name;
  const std::string path = mesh.find('/') == std::string::npos ? kMeshes + mesh : mesh;
  const int status = std::system(("timeout 300 " + kBinary + " optimize " + path + " " + options +
                                  " --quiet --no-timings -o " + base + ".ply --inner " + base + "_cavity.ply --outer-mesh " +
                                  base + "_outer.ply --report " + base + ".json 2>/dev/null")
                                     .c_str());
  Written w;
  w.exit_code = offsetopt::test::exit_code_of(status);
  w.report = Json::parse(read_file(base + ".json"));
  w.outer = read_mesh(base + "_outer.ply");
  w.cavity = read_mesh(base + "_cavity.ply");
  return w;
}

// Everything that makes the written cavity printable, measured on the files
// (tests/mass/geometry_checks.h: edge-through-triangle crossings, brute-force closest points).
void check_printable(const Written& w) {
  REQUIRE(w.cavity.F.rows() > 0);
  CHECK(closed_and_oriented(w.cavity));
  CHECK(test::self_intersections(w.cavity) == 0);
  CHECK(test::crossings_between(w.cavity, w.outer) == 0);
  const double wall = w.report.at("after").at("requested_wall").as_number();
  const double thinnest = test::min_vertex_distance(w.cavity, w.outer);
  CHECK(thinnest >= wall);
  CHECK(thinnest == doctest::Approx(w.report.at("after").at("min_wall_measured").as_number()).epsilon(1e-9));
}

Eigen::Vector3d mean_vertex(const Mesh& mesh) { return mesh.V.colwise().mean().transpose(); }

// Mass properties of the written solid: the outer surface less the cavity (tests/solid_checks.h).
test::MassFigures written_properties(const Written& w) {
  const Eigen::Vector3d origin = mean_vertex(w.outer);
  return test::mass_figures(test::minus(test::integrals_of(w.outer, origin), test::integrals_of(w.cavity, origin)), origin);
}

// The written solid spins: its centre of mass on the vertical through the tip, the inertia
// products Izx, Iyz vanishing (1e-4 of Izz), and Izz its largest principal moment.
void check_spins(const Written& w) {
  const test::MassFigures P = written_properties(w);
  const Json& tip = w.report.at("goal").at("tip");
  const double diagonal = w.report.at("frame").at("diagonal").as_number();
  CHECK(std::hypot(P.com.x() - tip.at(0).as_number(), P.com.y() - tip.at(1).as_number()) <= 1e-4 * diagonal);
  CHECK(std::fabs(P.inertia(2, 0)) <= 1e-4 * P.inertia(2, 2));
  CHECK(std::fabs(P.inertia(1, 2)) <= 1e-4 * P.inertia(2, 2));
  const double xx = P.inertia(0, 0), yy = P.inertia(1, 1), xy = P.inertia(0, 1);
  CHECK(0.5 * (xx + yy + std::hypot(xx - yy, 2.0 * xy)) < P.inertia(2, 2));
}

test::MassFigures properties_of(const Mesh& mesh) {
  const Eigen::Vector3d origin = mean_vertex(mesh);
  return test::mass_figures(test::integrals_of(mesh, origin), origin);
}

// The written solid floats fully submerged in `fluid_density`: the buoyancy of the outer volume
// equals the weight (1e-3 of it), the centre of mass is on the vertical through the centre of
// buoyancy and below it by the margin. Returns that depth.
double check_floats(const Written& w, double fluid_density) {
  const test::MassFigures P = written_properties(w);
  const test::MassFigures outer = properties_of(w.outer);
  const double diagonal = w.report.at("frame").at("diagonal").as_number();
  CHECK(std::fabs(fluid_density * outer.mass - P.mass) <= 1e-3 * P.mass);
  CHECK(std::hypot(P.com.x() - outer.com.x(), P.com.y() - outer.com.y()) <= 1e-4 * diagonal);
  const double depth = outer.com.z() - P.com.z();
  CHECK(depth >= w.report.at("parameters").at("margin").as_number());
  return depth;
}

// A mesh of ../shared/realposed's census, extracted into the test's folder; empty (and the test
// case skipped) when the folder is absent; a failure when the archive lacks it.
std::string census_mesh(const std::string& name) {
  const std::filesystem::path archive = test::shared_dir() / "realposed" / "meshes.tar.xz";
  if (!std::filesystem::exists(archive)) {
    test::skip_test("no " + archive.string());
    return "";
  }
  const std::string out = temp_dir() + "/" + name;
  if (!std::filesystem::exists(out))
    std::system(("tar -xJf " + archive.string() + " -C " + temp_dir() + " ./" + name + " 2>/dev/null").c_str());
  REQUIRE(std::filesystem::exists(out));
  return out;
}

}  // namespace

TEST_CASE("bottle stand: the contoured cavity is printable and the written solid stands by the margin") {
  const Written w = optimize("bottle", "bottle.obj", "--goal stand");
  CHECK(w.exit_code == 0);
  CHECK(w.report.at("cavity").at("written").as_string() == "contour");
  check_printable(w);
  const test::MassFigures P = written_properties(w);
  const double ground_tol = w.report.at("parameters").at("ground_tol").as_number();
  CHECK(test::support_margin(w.outer, ground_tol, P.com.head<2>()) >= w.report.at("parameters").at("margin").as_number());
}

TEST_CASE("bottle stand-filled --outer: the verified solid is the evidence that a void reaches the goal") {
  // The programme's mid reading adds the outer band but cannot shave the outer surface, and on
  // this bottle its best void falls short of the margin; the written solid reaches it, so the
  // report calls the goal reachable with the written solid as evidence, and its margin as the best.
  const Written w = optimize("bottle_filled", "bottle.obj", "--goal stand-filled --fill-density 0.8 --outer");
  REQUIRE(w.exit_code == 0);
  const Json& reach = w.report.at("reachability");
  CHECK(reach.at("reachable").as_bool());
  CHECK(reach.at("decided").as_bool());
  CHECK(reach.at("evidence").as_string() == "written solid");
  // Both margins of the files written: empty, and filled with liquid of density 0.8.
  const Eigen::Vector3d origin = mean_vertex(w.outer);
  const test::Integrals cavity = test::integrals_of(w.cavity, origin);
  const test::Integrals solid = test::minus(test::integrals_of(w.outer, origin), cavity);
  const Eigen::Vector3d empty = origin + solid.first / solid.volume;
  const Eigen::Vector3d filled = origin + (solid.first + 0.8 * cavity.first) / (solid.volume + 0.8 * cavity.volume);
  const double ground_tol = w.report.at("parameters").at("ground_tol").as_number();
  const double written = std::min(test::support_margin(w.outer, ground_tol, empty.head<2>()),
                                  test::support_margin(w.outer, ground_tol, filled.head<2>()));
  CHECK(written >= w.report.at("parameters").at("margin").as_number());
  CHECK(reach.at("best_margin").as_number() >= written - 1e-6 * w.report.at("frame").at("diagonal").as_number());
}

TEST_CASE("top spin: corrected until the written solid's centre of mass is on the axis and the products vanish") {
  const Written w = optimize("top", "top.obj", "--goal spin");
  CHECK(w.exit_code == 0);
  CHECK(w.report.at("cavity").at("written").as_string() == "contour");
  // Where a contour moved the centre of mass off the axis, the correction brought it back (with
  // the cavity at the requested wall, the first contour of this top may already meet it).
  const Json& rounds = w.report.at("cavity").at("rounds");
  REQUIRE(rounds.size() >= 1);
  for (std::size_t r = 0; r + 1 < rounds.size(); ++r) CHECK_FALSE(rounds.at(r).at("goal_met").as_bool());
  CHECK(rounds.at(rounds.size() - 1).at("goal_met").as_bool());
  check_printable(w);
  check_spins(w);
}

TEST_CASE("roly-poly: corrected until the written solid's centre of mass is under the sphere centre") {
  const Written w = optimize("rolypoly", "rolypoly.obj", "--goal roly-poly");
  CHECK(w.exit_code == 0);
  check_printable(w);
  const test::MassFigures P = written_properties(w);
  const Json& centre = w.report.at("goal").at("sphere_center");
  const double diagonal = w.report.at("frame").at("diagonal").as_number();
  CHECK(std::hypot(P.com.x() - centre.at(0).as_number(), P.com.y() - centre.at(1).as_number()) <= 1e-4 * diagonal);
  CHECK(P.com.z() < centre.at(2).as_number() - w.report.at("parameters").at("margin").as_number() * (1 - 1e-9));
}

TEST_CASE("bottle stand with a one-function basis: the offset void misses, the quadric void is written and stands") {
  // One basis function cannot lower the bottle's centre of mass far enough; the reachability
  // programme's optimal void can, and it is written instead.
  const Written w = optimize("bottle_k1", "bottle.obj", "--goal stand --k 1");
  CHECK(w.exit_code == 0);
  const Json& cavity = w.report.at("cavity");
  CHECK_FALSE(cavity.at("offset_goal_met").as_bool());
  CHECK(cavity.at("written").as_string() == "quadric");
  check_printable(w);
  const test::MassFigures P = written_properties(w);
  const double ground_tol = w.report.at("parameters").at("ground_tol").as_number();
  CHECK(test::support_margin(w.outer, ground_tol, P.com.head<2>()) >= w.report.at("parameters").at("margin").as_number());
  // The lowering achieved, from the written solid's and the input's own mass properties, against
  // the lowest centre of mass the programme finds any void reaching: at least 95% of it, and not
  // more than the programme's cell-scale estimate allows (2%).
  const Mesh input = read_mesh(kMeshes + "bottle.obj");
  const double zmin = input.V.col(2).minCoeff();
  const double before = properties_of(input).com.z() - zmin, written = P.com.z() - zmin;
  const double best = w.report.at("optimality").at("best").as_number();
  REQUIRE(before > best);
  const double fraction = (before - written) / (before - best);
  CHECK(fraction >= 0.95);
  CHECK(fraction <= 1.02);
  CHECK(fraction == doctest::Approx(w.report.at("optimality").at("fraction").as_number()).epsilon(1e-9));
}

TEST_CASE("top spin with a one-function basis: the offset void misses, the quadric void is written and spins") {
  // The programme's void at the lowest level it reaches (least ∫z) is written and corrected until
  // the written solid's centre of mass is on the axis, the products vanish and z is the axis of
  // its largest principal moment.
  const Written w = optimize("top_k1", "top.obj", "--goal spin --k 1");
  CHECK(w.exit_code == 0);
  const Json& cavity = w.report.at("cavity");
  CHECK_FALSE(cavity.at("offset_goal_met").as_bool());
  CHECK(cavity.at("written").as_string() == "quadric");
  check_printable(w);
  check_spins(w);
}

TEST_CASE("buoy float: the quadric void floats level, deeper than the offset void, from its first contour") {
  const Written w = optimize("buoy", "buoy.obj", "--goal float --fluid-density 0.806");
  CHECK(w.exit_code == 0);
  const Json& cavity = w.report.at("cavity");
  CHECK(cavity.at("written").as_string() == "quadric");
  check_printable(w);
  const double depth = check_floats(w, 0.806);
  CHECK(depth == doctest::Approx(w.report.at("optimality").at("written").as_number()).epsilon(1e-9));
  // Chosen on the offset model's prediction, before the offset surfaces' validity was searched
  // (offset_valid null, no offset objective). The offset void as --cavity offset writes it reaches
  // that prediction, far below the 95% that would have made it a candidate, and floats shallower.
  CHECK(cavity.at("offset_valid").is_null());
  CHECK(cavity.at("offset_objective").is_null());
  const std::string choice = cavity.at("choice").as_string();
  const std::string predicts = "the offset model predicts ";
  REQUIRE(choice.rfind(predicts, 0) == 0);
  const double predicted = std::stod(choice.substr(predicts.size())) / 100.0;
  const Written offset_void = optimize("buoy_offset", "buoy.obj", "--goal float --fluid-density 0.806 --cavity offset");
  REQUIRE(offset_void.exit_code == 0);
  const double offset_depth = check_floats(offset_void, 0.806);
  const double best = w.report.at("optimality").at("best").as_number();
  CHECK(std::fabs(offset_depth / best - predicted) <= 0.006);  // the choice rounds to a whole percent
  CHECK(offset_depth / best < 0.95);
  CHECK(depth > 1.01 * offset_depth);
  // The programme's optimum is a plane through a layer of cells it fills only in part; moved to
  // hold the programme's void (optimize/quadric_void.cpp), the first contour already holds the
  // void the balance asks for, (1 - 0.806) of the outer volume, within the check's 1e-3 of the mass.
  const Json& rounds = cavity.at("quadric_rounds");
  REQUIRE(rounds.size() >= 1);
  const double mass = written_properties(w).mass;
  CHECK(std::fabs(rounds.at(0).at("void_volume_contour").as_number() - (1.0 - 0.806) * properties_of(w.outer).mass) <= 1e-3 * mass);
}

TEST_CASE("volume below what the offset void can hold: a ball clipped to the carvable cells holds it") {
  // The offset void keeps the part of the band that the skeleton's gap leaves (on the demo sphere
  // about 2,965 of its 113,000), so a smaller target was refused as the tool's shortfall. Held by
  // the ball about the cells' middle: on the sphere, about its centre; on the torus, whose centroid
  // is in the hole, about the carvable cell nearest it.
  for (const auto& [mesh, target] : {std::pair<std::string, double>{"sphere.obj", 1000.0}, {"torus.obj", 176.0}}) {
    CAPTURE(mesh);
    const std::string name = "small_volume_" + mesh.substr(0, mesh.find('.'));
    const Written offset_only = optimize(name + "_offset", mesh, "--goal volume --cavity offset --target-volume " + format_double(target));
    CHECK(offset_only.exit_code == 3);
    const Written w = optimize(name, mesh, "--goal volume --target-volume " + format_double(target));
    CHECK(w.exit_code == 0);
    CHECK(w.report.at("cavity").at("written").as_string() == "quadric");
    check_printable(w);
    // The written cavity's own volume, from its faces: the target, within the check's 1e-4.
    CHECK(std::fabs(properties_of(w.cavity).mass - target) <= 1e-4 * target);
  }
}

TEST_CASE("a small volume with --outer: the ball is contoured a wall inside the thickened outer surface") {
  // Refused as the tool's shortfall before: the quadric void was only written inside the input.
  const Written w = optimize("small_volume_outer", "sphere.obj", "--goal volume --target-volume 1000 --outer");
  CHECK(w.exit_code == 0);
  CHECK(w.report.at("cavity").at("written").as_string() == "quadric");
  check_printable(w);
  CHECK(test::self_intersections(w.outer) == 0);
  CHECK(std::fabs(properties_of(w.cavity).mass - 1000.0) <= 1e-4 * 1000.0);
}

// Real meshes that some void reaches, once refused by the tool as its own shortfall.

TEST_CASE("real meshes: cgal-data_turbine floats at 0.8 (its quadric void's correction oscillated on the thin blades)") {
  const std::string mesh = census_mesh("cgal-data_turbine.ply");
  if (mesh.empty()) return;
  const Written w = optimize("turbine", mesh, "--goal float --fluid-density 0.8");
  CHECK(w.exit_code == 0);
  CHECK(w.report.at("cavity").at("written").as_string() == "quadric");
  check_printable(w);
  check_floats(w, 0.8);
}

TEST_CASE("real meshes: cgal-data_eight spins, and spins with the quadric void asked for") {
  // Refused as the tool's shortfall once; then the offset model missed spin and the quadric void
  // was written. Since the solver's first penalty is 100 (docs/solver.md) the offset model meets
  // it, and the contoured offset void is written: both ways it must spin.
  const std::string mesh = census_mesh("cgal-data_eight.ply");
  if (mesh.empty()) return;
  const Written w = optimize("eight", mesh, "--goal spin");
  CHECK(w.exit_code == 0);
  const std::string written = w.report.at("cavity").at("written").as_string();
  if (written != "quadric") CHECK(w.report.at("cavity").at("offset_goal_met").as_bool());
  check_printable(w);
  check_spins(w);
  const Written quadric = optimize("eight_quadric", mesh, "--goal spin --cavity quadric");
  CHECK(quadric.exit_code == 0);
  CHECK(quadric.report.at("cavity").at("written").as_string() == "quadric");
  check_printable(quadric);
  check_spins(quadric);
}
