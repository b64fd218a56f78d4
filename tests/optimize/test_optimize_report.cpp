// The report writer (cli/optimize_report.h): the library's typed result written as the report's
// JSON. Against the golden reports (tests/golden): the same keys in the same order for every
// object, and the same text when this build is the one that wrote them (as test_golden.cpp
// decides); and against hand-built expected text for the parts the golden cases do not reach.
#include <doctest/doctest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "../support.h"
#include "cli/cli_support.h"
#include "cli/optimize_report.h"
#include "meshio/load_input.h"
#include "io/json.h"
#include "optimize/offset_optimization.h"

using namespace offsetopt;
using offsetopt::test::read_file;

namespace {

const std::string kSource = OFFSETOPT_SOURCE_DIR;

// What `offsetopt --version` prints (cli/main.cpp), compared with the golden files' BUILD.txt.
bool same_build_as_golden() {
  const std::string version = std::string("offsetopt ") + OFFSETOPT_VERSION + "\nbuild: " + OFFSETOPT_BUILD_ID +
                              ", Eigen " + std::to_string(EIGEN_WORLD_VERSION) + "." +
                              std::to_string(EIGEN_MAJOR_VERSION) + "." + std::to_string(EIGEN_MINOR_VERSION) + "\n";
  return version == read_file(kSource + "/tests/golden/BUILD.txt");
}

// Every object's keys in order, recursively (array elements by index): the report's shape.
void collect_keys(const Json& j, const std::string& path, std::vector<std::string>& out) {
  if (j.type() == Json::Type::object) {
    for (const auto& [key, value] : j.items()) {
      out.push_back(path + "." + key);
      collect_keys(value, path + "." + key, out);
    }
  } else if (j.type() == Json::Type::array) {
    for (std::size_t i = 0; i < j.size(); ++i) collect_keys(j.at(i), path + "[" + std::to_string(i) + "]", out);
  }
}

// Runs the case as `optimize` does (meshio/load_input.h, one component) and compares the
// run's keys of the report with the golden file's.
void check_against_golden(const std::string& name, const std::string& mesh, const OptimizeOptions& options,
                          OptimizeStatus expected) {
  CAPTURE(name);
  LoadOptions load_options;
  load_options.single_component = true;
  const LoadedMesh loaded = load_input(kSource + "/meshes/" + mesh, load_options);
  const OptimizeResult result = optimize_offsets(loaded.mesh, options);
  REQUIRE(result.status == expected);
  const Json ours = cli::optimize_report(options, result);
  const Json golden = Json::parse(read_file(kSource + "/tests/golden/" + name + ".json"));
  // The golden report: input, format, vertices, faces, then the run's keys, then outputs.
  std::vector<std::string> golden_run_keys;
  for (const auto& item : golden.items())
    if (item.first != "input" && item.first != "format" && item.first != "vertices" && item.first != "faces" &&
        item.first != "outputs")
      golden_run_keys.push_back(item.first);
  std::vector<std::string> our_keys;
  for (const auto& item : ours.items()) our_keys.push_back(item.first);
  CHECK(our_keys == golden_run_keys);
  std::vector<std::string> our_paths, golden_paths;
  for (const auto& key : our_keys) {
    REQUIRE(golden.contains(key));
    collect_keys(ours.at(key), key, our_paths);
    collect_keys(golden.at(key), key, golden_paths);
  }
  CHECK(our_paths == golden_paths);
  if (!same_build_as_golden()) return;
  // The whole text, as `optimize` writes it: the command's own keys (strings and counts, which
  // parse back exactly) taken from the golden file around the writer's. The text, not parsed
  // values: "-0" and "0" parse alike.
  Json full = Json::object();
  full["input"] = golden.at("input");
  full["format"] = loaded.format;
  full["vertices"] = static_cast<long long>(loaded.mesh.V.rows());
  full["faces"] = static_cast<long long>(loaded.mesh.F.rows());
  for (const auto& item : ours.items()) full[item.first] = item.second;
  full["outputs"] = golden.at("outputs");
  CHECK(full.dump(2) == read_file(kSource + "/tests/golden/" + name + ".json"));
}

}  // namespace

TEST_CASE("optimize report: the writer gives the golden reports' keys, order and (same build) text") {
  OptimizeOptions volume = OptimizeOptions::defaults();
  volume.goal = GoalKind::volume;
  volume.target_volume = 20000;
  check_against_golden("sphere_volume", "sphere.obj", volume, OptimizeStatus::verified);

  OptimizeOptions roly = OptimizeOptions::defaults();
  roly.goal = GoalKind::roly_poly;
  check_against_golden("rolypoly", "rolypoly.obj", roly, OptimizeStatus::verified);

  OptimizeOptions spin_k2 = OptimizeOptions::defaults();  // goal not met: the report says why
  spin_k2.goal = GoalKind::spin;
  spin_k2.k = 2;
  check_against_golden("capsule_k2", "capsule.obj", spin_k2, OptimizeStatus::goal_not_met);
}

TEST_CASE("optimize report: a verification without validity figures, and the stage timings") {
  Verification v;
  v.goal.goal = GoalKind::volume;
  v.goal.mass = 1.5;
  v.goal.void_volume = 0.25;
  v.goal.outer_volume = 1.75;
  v.goal.center_of_mass = Eigen::Vector3d(0.5, -0.5, 2.0);
  v.goal.target_volume = 0.25;
  v.goal.volume_relative_error = -0.125;
  v.goal_met = true;
  v.failures = {"the cavity could not be contoured: too many nodes"};
  // Not measured (a contour to be corrected): goal_met, failures, then valid.
  CHECK(cli::verification_json(v).dump(2) ==
        "{\n"
        "  \"mass\": 1.5,\n"
        "  \"void_volume\": 0.25,\n"
        "  \"outer_volume\": 1.75,\n"
        "  \"center_of_mass\": [0.5, -0.5, 2],\n"
        "  \"target_volume\": 0.25,\n"
        "  \"volume_relative_error\": -0.125,\n"
        "  \"goal_met\": true,\n"
        "  \"failures\": [\"the cavity could not be contoured: too many nodes\"],\n"
        "  \"valid\": false\n"
        "}\n");
  // Measured, with no cavity vertex measured: the wall is null.
  ValidityFigures& figures = v.validity.emplace();
  figures.inner_self_intersections = 3;
  figures.requested_wall = 0.5;
  figures.min_wall_vertex = -1;
  v.failures.clear();
  v.valid = true;
  CHECK(cli::verification_json(v).dump(-1) ==
        "{\"mass\":1.5,\"void_volume\":0.25,\"outer_volume\":1.75,\"center_of_mass\":[0.5,-0.5,2],"
        "\"target_volume\":0.25,\"volume_relative_error\":-0.125,\"inner_self_intersections\":3,"
        "\"inner_outer_crossings\":0,\"cavity_unmatched_edges\":0,\"requested_wall\":0.5,\"min_wall_measured\":null,"
        "\"min_wall_vertex\":-1,\"largest_bound_violation\":0,\"goal_met\":true,\"valid\":true,\"failures\":[]}");

  StageTimings t;
  t.frame = 0.25;
  t.total = 2.5;
  CHECK(cli::stage_timings_json(t).dump(-1) == "{\"frame\":0.25,\"skeleton\":0,\"basis\":0,\"solve\":0,\"verify\":0,\"total\":2.5}");
  t.contour = 1.0;
  t.correct = 0.5;
  CHECK(cli::stage_timings_json(t).dump(-1) ==
        "{\"frame\":0.25,\"skeleton\":0,\"basis\":0,\"solve\":0,\"verify\":0,\"contour\":1,\"correct\":0.5,\"total\":2.5}");
}
