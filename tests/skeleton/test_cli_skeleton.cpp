// `offsetopt skeleton` end to end through the built binary: the contracted mesh keeps the input's
// connectivity and matches the library, the JSON report carries the statistics, two runs are
// byte-identical (mesh and report minus the *seconds fields), bad usage exits 2 with one line.
// Real meshes from ../shared/meshes ($OFFSETOPT_SHARED_DIR/meshes) are contracted when present
// (CTest reports the case skipped otherwise).
#include <doctest/doctest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "../support.h"
#include "io/json.h"
#include "meshio/load_mesh.h"
#include "skeleton/laplacian_contraction.h"

using namespace offsetopt;
using offsetopt::test::read_file;
using offsetopt::test::RunResult;

namespace {

const std::filesystem::path& scratch_dir() {
  struct Scratch {
    std::filesystem::path path;
    Scratch() : path(std::filesystem::temp_directory_path() / ("offsetopt_test_skeleton_" + std::to_string(::getpid()))) {
      std::filesystem::create_directories(path);
    }
    ~Scratch() {
      std::error_code ignored;
      std::filesystem::remove_all(path, ignored);
    }
  };
  static const Scratch scratch;
  return scratch.path;
}

std::string temp(const std::string& name) { return (scratch_dir() / name).string(); }

RunResult run(const std::string& arguments) {
  static int counter = 0;
  const std::string out = temp("out" + std::to_string(counter) + ".txt");
  const std::string err = temp("err" + std::to_string(counter++) + ".txt");
  const std::string command = std::string("timeout 120 '") + OFFSETOPT_BINARY + "' " + arguments + " >'" + out + "' 2>'" + err + "'";
  const int status = std::system(command.c_str());
  RunResult result;
  result.exit_code = offsetopt::test::exit_code_of(status);
  result.out = read_file(out);
  result.err = read_file(err);
  return result;
}

// The report without its timing fields (every key ending in "seconds").
Json without_seconds(const Json& report) {
  Json out = Json::object();
  for (const auto& [key, value] : report.items())
    if (key.size() < 7 || key.compare(key.size() - 7, 7, "seconds") != 0) out.set(key, value);
  return out;
}

const std::string kSource = OFFSETOPT_SOURCE_DIR;

}  // namespace

TEST_CASE("skeleton writes the contracted mesh with the input's connectivity and a report") {
  const std::string input = kSource + "/meshes/torus.obj";
  const std::string output = temp("torus_skeleton.obj"), json = temp("torus.json");
  const RunResult r = run("skeleton '" + input + "' -o '" + output + "' --json '" + json + "' --wall 0.8");
  REQUIRE(r.exit_code == 0);
  CHECK(r.err.find("skeleton:") != std::string::npos);  // progress on stderr
  const Mesh in = load_mesh(input).mesh;
  const Mesh out = load_mesh(output).mesh;
  REQUIRE(out.V.rows() == in.V.rows());
  CHECK(out.F == in.F);
  // The same positions the library computes (the OBJ holds shortest round-trip doubles).
  const ContractionResult expected = laplacian_contraction(in.V, in.F);
  CHECK((out.V - expected.V).cwiseAbs().maxCoeff() == 0.0);

  const Json report = Json::parse(read_file(json));
  CHECK(report.at("vertices").as_integer() == in.V.rows());
  CHECK(report.at("skeleton").at("steps").as_integer() == expected.steps);
  CHECK(report.at("skeleton").at("volume_ratio").as_number() == expected.volume_ratio);
  CHECK(report.at("skeleton").at("area_ratio").as_number() == expected.area_ratio);
  CHECK(report.at("skeleton").at("status").as_string() == "volume_ratio_reached");
  CHECK(report.at("skeleton").at("history").size() == static_cast<std::size_t>(expected.steps));
  for (const char* key : {"shortened", "fallback", "shallow", "immobile", "band_empty"}) CHECK(report.at("offset_field").contains(key));
  CHECK(report.at("seconds").as_number() >= 0.0);
  CHECK(report.at("total_seconds").as_number() >= report.at("seconds").as_number());
}

TEST_CASE("two skeleton runs are byte-identical (mesh file, and the report minus seconds)") {
  const std::string input = kSource + "/meshes/bottle.obj";
  std::string meshes[2], reports[2];
  for (int k = 0; k < 2; ++k) {
    const std::string output = temp("bottle_" + std::to_string(k) + ".ply");
    const std::string json = temp("bottle_" + std::to_string(k) + ".json");
    REQUIRE(run("skeleton '" + input + "' -o '" + output + "' --json '" + json + "' --quiet").exit_code == 0);
    meshes[k] = read_file(output);
    reports[k] = without_seconds(Json::parse(read_file(json))).dump(2);
  }
  REQUIRE(!meshes[0].empty());
  CHECK(meshes[0] == meshes[1]);
  // The output paths differ by name only; compare the rest.
  CHECK(reports[0].size() == reports[1].size());
  const Json a = Json::parse(reports[0]), b = Json::parse(reports[1]);
  for (const auto& [key, value] : a.items())
    if (key != "output") CHECK(value.dump(0) == b.at(key).dump(0));
}

TEST_CASE("skeleton JSON to stdout, mesh to a file") {
  const std::string input = kSource + "/meshes/sphere.obj";
  const RunResult r = run("skeleton '" + input + "' -o '" + temp("s.stl") + "' --json - --quiet");
  REQUIRE(r.exit_code == 0);
  CHECK(r.err.empty());
  const Json report = Json::parse(r.out);
  CHECK(report.at("faces").as_integer() == 5120);
  CHECK(load_mesh(temp("s.stl")).mesh.F.rows() == 5120);
}

TEST_CASE("skeleton usage errors exit 2 with one Error line") {
  const std::string input = kSource + "/meshes/sphere.obj";
  auto one_error_line = [](const RunResult& r) {
    CHECK(r.exit_code == 2);
    CHECK(r.err.rfind("Error: ", 0) == 0);
    CHECK(r.err.find('\n') == r.err.size() - 1);
  };
  one_error_line(run("skeleton '" + input + "'"));                                       // no -o
  one_error_line(run("skeleton -o '" + temp("x.obj") + "'"));                            // no mesh
  one_error_line(run("skeleton '" + input + "' -o '" + temp("x.obj") + "' --max-steps 0"));
  one_error_line(run("skeleton '" + input + "' -o '" + temp("x.obj") + "' --wall -1"));
  one_error_line(run("skeleton '" + input + "' -o '" + temp("x.obj") + "' --frobnicate"));
  one_error_line(run("skeleton '" + input + "' -o '" + temp("x.xyz") + "'"));            // unknown format
  one_error_line(run("skeleton '" + temp("missing.obj") + "' -o '" + temp("x.obj") + "'"));
  one_error_line(run("skeleton '" + input + "' -o - --json -"));
  // Never overwrites its input.
  const std::string copy = temp("copy.obj");
  std::filesystem::copy_file(input, copy);
  one_error_line(run("skeleton '" + copy + "' -o '" + copy + "'"));
  CHECK(read_file(copy) == read_file(input));
  const RunResult help = run("skeleton --help");
  CHECK(help.exit_code == 0);
  CHECK(help.out.find("usage: offsetopt skeleton") == 0);
}

TEST_CASE("real meshes from the shared folder contract and report (skipped when absent)") {
  const std::filesystem::path folder = offsetopt::test::shared_dir() / "meshes";
  if (!std::filesystem::exists(folder / "kitten_lowres.obj")) {
    offsetopt::test::skip_test((folder / "kitten_lowres.obj").string() + " is absent");
    return;
  }
  for (const char* name : {"kitten_lowres.obj", "rocker_arm.off", "elephant.off"}) {
    if (!std::filesystem::exists(folder / name)) continue;
    CAPTURE(name);
    const RunResult r = run("skeleton '" + (folder / name).string() + "' -o '" + temp("real.obj") + "' --json - --quiet");
    REQUIRE(r.exit_code == 0);
    const Json report = Json::parse(r.out);
    CHECK(report.at("skeleton").at("volume_ratio").as_number() < 0.5);
    CHECK(report.at("offset_field").at("fallback").as_integer() < report.at("vertices").as_integer());
  }
}
