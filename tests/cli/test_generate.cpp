// The built binary end to end: `generate` writes the library's demo meshes exactly (and the
// committed copies are those files),
// `inspect` reports what the library computes and says the leaning bottle falls, and bad usage
// exits with code 2 and one "Error:" line.
#include <doctest/doctest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "../support.h"
#include "io/json.h"
#include "mass/mass_properties.h"
#include "mesh/demo_meshes.h"
#include "meshio/read_raw_mesh.h"

using namespace offsetopt;
using offsetopt::test::read_file;
using offsetopt::test::RunResult;

namespace {

// A scratch directory for this process, removed with everything in it at exit.
const std::filesystem::path& scratch_dir() {
  struct Scratch {
    std::filesystem::path path;
    Scratch() : path(std::filesystem::temp_directory_path() / ("offsetopt_test_cli_" + std::to_string(::getpid()))) {
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

std::filesystem::path temp_path(const std::string& name) { return scratch_dir() / name; }

// Runs the offsetopt binary with `arguments` (already shell-quoted where needed).
RunResult run(const std::string& arguments) {
  static int counter = 0;
  const auto out = temp_path("out" + std::to_string(counter) + ".txt");
  const auto err = temp_path("err" + std::to_string(counter++) + ".txt");
  const std::string command = std::string("'") + OFFSETOPT_BINARY + "' " + arguments + " >'" + out.string() + "' 2>'" + err.string() + "'";
  const int status = std::system(command.c_str());
  RunResult result;
  result.exit_code = offsetopt::test::exit_code_of(status);
  result.out = read_file(out);
  result.err = read_file(err);
  return result;
}

const std::string kSource = OFFSETOPT_SOURCE_DIR;

Mesh read_back(const std::string& path) {
  const RawMesh raw = read_raw_mesh(path);
  return Mesh{raw.V, raw.F};
}

}  // namespace

// The demo meshes themselves are checked against independent figures in tests/mass/test_demo_meshes.cpp;
// here the command must write exactly those meshes (read back: the same doubles, the same faces),
// and the committed copies in meshes/, which other tests and the README read, must still be them.
TEST_CASE("generate writes each library demo mesh exactly, and the committed meshes/NAME.obj are those files") {
  const RunResult list = run("generate --list");
  REQUIRE(list.exit_code == 0);
  std::string expected_list;
  for (const auto& name : demo_mesh_names()) expected_list += name + "\n";
  CHECK(list.out == expected_list);
  for (const auto& name : demo_mesh_names()) {
    CAPTURE(name);
    const auto path = temp_path(name + ".obj");
    const RunResult r = run("generate " + name + " -o '" + path.string() + "'");
    REQUIRE(r.exit_code == 0);
    CHECK(r.err.empty());
    const std::string committed = read_file(kSource + "/meshes/" + name + ".obj");
    REQUIRE(!committed.empty());
    CHECK(read_file(path) == committed);
    const Mesh written = read_back(path.string()), expected = make_demo_mesh(name);
    CHECK(written.F == expected.F);
    CHECK(written.V == expected.V);
    std::filesystem::remove(path);
  }
}

TEST_CASE("inspect reports the library's numbers and that the leaning bottle falls over") {
  const std::string bottle = "'" + kSource + "/meshes/bottle.obj'";
  const RunResult r = run("inspect " + bottle + " --json -");
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("\"stands\": false") != std::string::npos);
  const Json report = Json::parse(r.out);
  const Vector10d P = mass_properties(make_demo_mesh("bottle"));  // the file holds these vertices exactly
  CHECK(report.at("vertices").as_integer() == make_demo_mesh("bottle").V.rows());
  CHECK(report.at("volume").as_number() == doctest::Approx(P(kMass)).epsilon(1e-15));
  CHECK(report.at("center_of_mass").at(0).as_number() == doctest::Approx(P(kCx)).epsilon(1e-15));
  CHECK(report.at("inertia").at("zx").as_number() == doctest::Approx(P(kIzx)).epsilon(1e-15));
  const Json& stability = report.at("stability");
  CHECK_FALSE(stability.at("stands").as_bool());
  CHECK(stability.at("com_margin").as_number() < 0.0);
  CHECK(stability.at("support_polygon").size() == 64);
  CHECK(stability.at("ground_tol").as_number() > 0.0);

  // Same input, same bytes; a JSON file equals the stdout JSON.
  CHECK(run("inspect " + bottle + " --json -").out == r.out);
  const auto json_file = temp_path("bottle.json");
  REQUIRE(run("inspect " + bottle + " --json '" + json_file.string() + "'").exit_code == 0);
  CHECK(read_file(json_file) == r.out);

  // A larger ground tolerance takes in more contact vertices; the summary says it falls.
  const Json loose = Json::parse(run("inspect " + bottle + " --json - --ground-tol 5").out);
  CHECK(loose.at("stability").at("contact_vertices").as_integer() > stability.at("contact_vertices").as_integer());
  const RunResult summary = run("inspect " + bottle);
  CHECK(summary.exit_code == 0);
  CHECK(summary.out.find("falls over") != std::string::npos);

  const Json torus = Json::parse(run("inspect '" + kSource + "/meshes/torus.obj' --json -").out);
  CHECK(torus.at("stability").at("stands").as_bool());
}

TEST_CASE("generate --detail scales the vertex count by about detail squared and keeps the mass properties") {
  // The same profile sampled finer: the volume and centre of mass converge to the coarse mesh's
  // (both approximate one smooth solid), the vertex count grows as detail².
  for (const char* name : {"bottle", "buoy"}) {
    CAPTURE(name);
    const Mesh coarse = make_demo_mesh(name), fine = make_demo_mesh(name, 2.0);
    const double ratio = static_cast<double>(fine.V.rows()) / static_cast<double>(coarse.V.rows());
    CHECK(ratio > 3.5);
    CHECK(ratio < 4.5);
    const Vector10d P = mass_properties(coarse), Q = mass_properties(fine);
    CHECK(Q(kMass) == doctest::Approx(P(kMass)).epsilon(0.01));
    CHECK(Q(kCz) == doctest::Approx(P(kCz)).epsilon(0.01));
  }
  const RunResult r = run("generate bottle --detail 0.5 -o '" + temp_path("half.obj").string() + "'");
  CHECK(r.exit_code == 0);
  CHECK(run("check '" + temp_path("half.obj").string() + "' --quiet").exit_code == 0);
}

TEST_CASE("bad usage: exit code 2 and one Error line") {
  const std::string bottle = "'" + kSource + "/meshes/bottle.obj'";
  for (const std::string& arguments :
       {std::string("generate teapot -o x.obj"), std::string("generate bottle"), std::string("generate"),
        std::string("generate bottle -o '") + temp_path("no/such/dir/x.obj").string() + "'", std::string("generate bottle -o x.xyz"),
        std::string("inspect"), std::string("inspect /no/such/file.obj"), "inspect " + bottle + " --ground-tol -1",
        "inspect " + bottle + " --ground-tol abc", "inspect " + bottle + " --bogus", "inspect " + bottle + " --json",
        "inspect " + bottle + " " + bottle, std::string("generate sphere --detail 2 -o x.obj"),
        std::string("generate bottle --detail 100 -o x.obj")}) {
    CAPTURE(arguments);
    const RunResult r = run(arguments);
    CHECK(r.exit_code == 2);
    CHECK(r.err.rfind("Error: ", 0) == 0);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  }
  const RunResult help = run("inspect --help");
  CHECK(help.exit_code == 0);
  CHECK(help.out.find("default: 1e-3 x the bounding-box diagonal") != std::string::npos);
  CHECK(run("generate --help").exit_code == 0);
}
