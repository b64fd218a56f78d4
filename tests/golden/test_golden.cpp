// Golden files (tests/golden): every case of cases.txt (one CTest test each) is run through the
// binary and its report and printable solid are compared with the stored ones. When `offsetopt
// --version` names the build recorded in BUILD.txt the comparison is byte for byte (the report's
// "input" path aside); for any other build (another compiler, another CPU, a sanitizer build) it
// is within stated tolerances, because the solver's path may differ in the last bits and so in
// its counts:
//   report: the same keys and strings, numbers within 1e-3 relative plus 1e-6 of the diagonal,
//           vertex counts within 2% or 3, except the solver's counters, status and objective,
//           the basis' status, the index of the thinnest wall and the failure texts (how the
//           path went, not what came out);
//   solid:  the SHA-256 of the written PLY (NAME.ply.sha256: a contoured cavity has 10^5 faces,
//           too many to keep in the repository for each case) for the same build; for another
//           build a contoured cavity may cut other grid cells, so the solid written with exit 0
//           is checked by itself (check_solid_independently): closed and oriented, its mass and
//           centre of mass the report's, its goal met, measured here without the tool's code.
// tests/golden/regenerate.sh rewrites them after an intended change.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>

#include "../mesh_checks.h"
#include "../solid_checks.h"
#include "../support.h"
#include "../temp_dir.h"
#include "io/json.h"
#include "meshio/read_raw_mesh.h"

using offsetopt::Json;
using offsetopt::test::read_file;

namespace {

const std::string kBinary = OFFSETOPT_BINARY;
const std::string kSource = OFFSETOPT_SOURCE_DIR;
const std::string kGolden = kSource + "/tests/golden/";

// Removed with everything in it when the test executable exits.
const std::string& temp_dir() {
  static const TempDir dir("offsetopt-golden");
  return dir.path();
}

int run(const std::string& command) {
  const int status = std::system(command.c_str());
  REQUIRE(status != -1);
  return offsetopt::test::exit_code_of(status);
}

struct Case {
  std::string name, mesh, options;
  int exit_code = 0;
};

std::vector<Case> read_cases() {
  std::vector<Case> cases;
  std::istringstream in(read_file(kGolden + "cases.txt"));
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> fields;
    std::size_t start = 0;
    for (std::size_t bar; (bar = line.find('|', start)) != std::string::npos; start = bar + 1)
      fields.push_back(line.substr(start, bar - start));
    fields.push_back(line.substr(start));
    REQUIRE(fields.size() == 4);
    cases.push_back({fields[0], fields[2], fields[3], std::stoi(fields[1])});
  }
  return cases;
}

// The report with its "input" path (which names where the mesh was read from) blanked.
std::string without_input_path(std::string report) {
  const std::string key = "\"input\": \"";
  const std::size_t at = report.find(key);
  if (at == std::string::npos) return report;
  const std::size_t end = report.find('"', at + key.size());
  return report.replace(at + key.size(), end - at - key.size(), "MESH");
}

std::string compact(const Json& value) {
  std::string text = value.dump(0);
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return text.size() > 80 ? text.substr(0, 77) + "..." : text;
}

// Keys whose values describe the solver's path rather than the result, or name which of many
// equal candidates won (an argmin on a symmetric mesh), or are text with numbers inside.
const std::set<std::string> kPathKeys = {"evaluations", "outer_iterations", "inner_iterations", "repair_rounds",
                                         "repairs",     "status",           "objective",        "input",
                                         "rounds",
                                         "min_wall_vertex", "failures",     "why"};

void compare_json(const Json& expected, const Json& actual, const std::string& where, double absolute,
                  std::vector<std::string>& differences) {
  if (differences.size() > 20) return;
  const bool numbers = (expected.type() == Json::Type::number || expected.type() == Json::Type::integer) &&
                       (actual.type() == Json::Type::number || actual.type() == Json::Type::integer);
  if (expected.type() == Json::Type::integer && actual.type() == Json::Type::integer) {
    // Counts of vertices (clamped, left solid, ...): a vertex at a threshold may fall either way.
    const double a = expected.as_number(), b = actual.as_number();
    if (std::fabs(a - b) > std::max(3.0, 0.02 * std::max(std::fabs(a), std::fabs(b))))
      differences.push_back(where + ": " + compact(expected) + " against " + compact(actual));
    return;
  }
  if (numbers) {
    const double a = expected.as_number(), b = actual.as_number();
    if (std::fabs(a - b) > 1e-3 * std::max(std::fabs(a), std::fabs(b)) + absolute)
      differences.push_back(where + ": " + compact(expected) + " against " + compact(actual));
    return;
  }
  if (expected.type() != actual.type()) {
    differences.push_back(where + ": " + compact(expected) + " against " + compact(actual));
    return;
  }
  switch (expected.type()) {
    case Json::Type::object: {
      if (expected.items().size() != actual.items().size()) differences.push_back(where + ": different keys");
      for (const auto& [key, value] : expected.items()) {
        if (kPathKeys.count(key)) continue;
        if (!actual.contains(key)) {
          differences.push_back(where + "." + key + ": missing");
          continue;
        }
        compare_json(value, actual.at(key), where + "." + key, absolute, differences);
      }
      break;
    }
    case Json::Type::array:
      if (expected.size() != actual.size()) {
        differences.push_back(where + ": " + std::to_string(expected.size()) + " elements against " +
                              std::to_string(actual.size()));
        break;
      }
      for (std::size_t i = 0; i < expected.size(); ++i)
        compare_json(expected.at(i), actual.at(i), where + "[" + std::to_string(i) + "]", absolute, differences);
      break;
    default:
      if (compact(expected) != compact(actual))
        differences.push_back(where + ": " + compact(expected) + " against " + compact(actual));
  }
}


Eigen::Vector3d vector_of(const Json& array) {
  return Eigen::Vector3d(array.at(0).as_number(), array.at(1).as_number(), array.at(2).as_number());
}

// Off the golden build the written solid is checked on its own, by code independent of the
// tool's (tests/solid_checks.h): closed and oriented (tests/mesh_checks.h), the report's mass and
// centre of mass are the file's, and the goal holds with the thresholds the tool verifies
// (cavity/verify_offsets.cpp) plus round-off.
void check_solid_independently(const offsetopt::Mesh& solid, const Json& report) {
  using offsetopt::test::SolidFigures;
  using offsetopt::test::support_margin;
  REQUIRE(solid.F.rows() > 0);
  CHECK(offsetopt::test::closed_and_oriented(solid));
  const double diagonal = report.at("frame").at("diagonal").as_number();
  const Json& parameters = report.at("parameters");
  const Json& after = report.at("after");
  const SolidFigures figures = offsetopt::test::measure_solid(solid);
  const offsetopt::test::MassFigures material = offsetopt::test::mass_figures(figures.solid, figures.origin);
  const double mass = material.mass, outer_volume = figures.outer.volume;
  const Eigen::Vector3d com = material.com;
  // The report's figures are measured on the solid as written.
  CHECK(std::fabs(mass - after.at("mass").as_number()) <= 1e-6 * mass);
  CHECK((com - vector_of(after.at("center_of_mass"))).norm() <= 1e-6 * diagonal);
  const std::string goal = report.at("goal").at("name").as_string();
  CAPTURE(goal);
  const double position_tol = 1e-4 * diagonal, slack = 1e-6 * diagonal;
  if (goal == "stand" || goal == "stand-filled") {
    const double margin = parameters.at("margin").as_number(), ground_tol = parameters.at("ground_tol").as_number();
    const double empty_margin = support_margin(solid, ground_tol, com.head<2>());
    CHECK(empty_margin >= margin - slack);
    CHECK(std::fabs(empty_margin - after.at("empty").at("com_margin").as_number()) <= slack);
    if (goal == "stand-filled") {
      const double rho = parameters.at("fill_density").as_number();
      const Eigen::Vector3d void_first = figures.outer.first - figures.solid.first;
      const double void_volume = outer_volume - mass;
      const Eigen::Vector3d filled = figures.origin + (figures.solid.first + rho * void_first) / (mass + rho * void_volume);
      const double filled_margin = support_margin(solid, ground_tol, filled.head<2>());
      CHECK(filled_margin >= margin - slack);
      CHECK(std::fabs(filled_margin - after.at("filled").at("com_margin").as_number()) <= slack);
    }
  } else if (goal == "volume") {
    const double target = parameters.at("target_volume").as_number();
    CHECK(std::fabs(outer_volume - mass - target) <= 1e-4 * target * (1.0 + 1e-6));
  } else if (goal == "float") {
    const double rho = parameters.at("fluid_density").as_number();
    const Eigen::Vector3d buoyancy = figures.origin + figures.outer.first / outer_volume;
    CHECK(std::fabs(rho * outer_volume - mass) <= 1e-3 * mass * (1.0 + 1e-6));
    CHECK(std::hypot(com.x() - buoyancy.x(), com.y() - buoyancy.y()) <= position_tol + slack);
    CHECK(com.z() < buoyancy.z());
  } else if (goal == "spin" || goal == "roly-poly") {
    const Eigen::Vector3d axis = vector_of(report.at("goal").at(goal == "spin" ? "tip" : "sphere_center"));
    CHECK(std::hypot(com.x() - axis.x(), com.y() - axis.y()) <= position_tol + slack);
    if (goal == "roly-poly") {
      CHECK(com.z() < axis.z());
    } else {
      const Eigen::Matrix3d& I = material.inertia;
      CHECK(std::fabs(I(0, 2)) <= 1e-4 * I(2, 2) * (1.0 + 1e-3));
      CHECK(std::fabs(I(1, 2)) <= 1e-4 * I(2, 2) * (1.0 + 1e-3));
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> principal(I);
      int closest = 0;
      for (int a = 1; a < 3; ++a)
        if (std::fabs(principal.eigenvectors()(2, a)) > std::fabs(principal.eigenvectors()(2, closest))) closest = a;
      CHECK(closest == 2);  // eigenvalues ascending: the axis nearest z has the largest moment
    }
  }
}

}  // namespace

// CTest runs one case per test (tests/CMakeLists.txt sets OFFSETOPT_GOLDEN_CASE to its name);
// run by hand without it, every case runs.
TEST_CASE("golden files: every case's report and solid match the stored ones (exactly for the same build)") {
  const std::string version_file = temp_dir() + "/version.txt";
  REQUIRE(run(kBinary + " --version > " + version_file) == 0);
  // OFFSETOPT_GOLDEN_TOLERANT=1 takes the other builds' path on this one (to test that path).
  const bool same_build =
      read_file(version_file) == read_file(kGolden + "BUILD.txt") && !std::getenv("OFFSETOPT_GOLDEN_TOLERANT");
  MESSAGE(std::string(same_build ? "same build as the golden files: byte comparison"
                                  : "another build than the golden files: comparison within tolerances"));
  std::vector<Case> cases = read_cases();
  CHECK(cases.size() >= 10);
  if (const char* only = std::getenv("OFFSETOPT_GOLDEN_CASE")) {
    cases.erase(std::remove_if(cases.begin(), cases.end(), [&](const Case& c) { return c.name != only; }), cases.end());
    INFO("OFFSETOPT_GOLDEN_CASE=", only);
    REQUIRE(cases.size() == 1);
  }
  for (const Case& c : cases) {
    CAPTURE(c.name);
    const std::string base = temp_dir() + "/" + c.name;
    // Each option word single-quoted for the shell (cases.txt has words like z>240).
    std::string quoted;
    std::istringstream words(c.options);
    for (std::string word; words >> word;) quoted += " '" + word + "'";
    const int code = run("cd " + temp_dir() + " && timeout 600 " + kBinary + " optimize " + kSource + "/meshes/" + c.mesh +
                         quoted + " --quiet --no-timings -o " + c.name + ".ply --report " + c.name + ".json 2>/dev/null");
    CHECK(code == c.exit_code);
    const std::string report = read_file(base + ".json"), golden_report = read_file(kGolden + c.name + ".json");
    REQUIRE_FALSE(golden_report.empty());
    if (same_build) {
      CHECK(without_input_path(report) == without_input_path(golden_report));
      REQUIRE(run("cd " + temp_dir() + " && sha256sum " + c.name + ".ply > " + c.name + ".ply.sha256") == 0);
      CHECK(read_file(base + ".ply.sha256") == read_file(kGolden + c.name + ".ply.sha256"));
      continue;
    }
    const Json expected = Json::parse(golden_report), actual = Json::parse(report);
    const double diagonal = expected.at("frame").at("diagonal").as_number();
    std::vector<std::string> differences;
    compare_json(expected, actual, "report", 1e-6 * diagonal, differences);
    for (const std::string& d : differences) MESSAGE(d);
    CHECK(differences.empty());
    const offsetopt::RawMesh solid = offsetopt::read_raw_mesh(base + ".ply");
    if (c.exit_code == 0) check_solid_independently(offsetopt::Mesh{solid.V, solid.F}, actual);
  }
}
