// 3MF through the real binary (issue 14): `optimize` writes the printable solid as one 3MF
// object with both shells, which `inspect` reads back with the mass the report states; a 3MF
// input's unit carries over to the 3MF outputs unless --unit says otherwise.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "../meshio/meshio_test_util.h"
#include "io/json.h"

using namespace meshio_test;

namespace {

std::string model_of(const TempDir& dir, const std::string& package) {
  const std::string list = dir.file("model.xml");
  const std::string command = "/usr/bin/unzip -p " + shell_quote(package) + " 3D/3dmodel.model > " + shell_quote(list);
  return std::system(command.c_str()) == 0 ? read_file(list) : std::string();
}

}  // namespace

TEST_CASE("3MF end to end: optimize writes one object with both shells, inspect reads the report's mass, units carry over") {
  TempDir dir;
  const std::string in = dir.file("sphere.3mf"), out = dir.file("solid.3mf"), report = dir.file("report.json");
  REQUIRE(run_offsetopt("generate sphere -o " + shell_quote(in) + " --unit inch", dir).exit_code == 0);
  const RunResult run = run_offsetopt("optimize " + shell_quote(in) + " --goal volume --target-volume 20000 --no-timings -o " +
                                          shell_quote(out) + " --report " + shell_quote(report),
                                      dir);
  CAPTURE(run.err);
  REQUIRE(run.exit_code == 0);
  CHECK(run.err.find("Warning: 3MF unit is inch") != std::string::npos);

  const RunResult inspect = run_offsetopt("inspect " + shell_quote(out) + " --json -", dir);
  REQUIRE(inspect.exit_code == 0);
  CHECK(inspect.err.find("2 separate closed shells") != std::string::npos);  // outer surface and cavity
  offsetopt::Json measured = offsetopt::Json::parse(inspect.out);
  offsetopt::Json stated = offsetopt::Json::parse(read_file(report));
  const double mass = stated["after"]["mass"].as_number();
  CHECK(std::abs(measured["volume"].as_number() - mass) <= 1e-9 * mass);

  INFO("scripts/deps.sh installs unzip");
  REQUIRE(::access("/usr/bin/unzip", X_OK) == 0);
  const std::string model = model_of(dir, out);
  CHECK(model.find("<model unit=\"inch\"") != std::string::npos);
  std::size_t objects = 0;
  for (std::size_t at = model.find("<object "); at != std::string::npos; at = model.find("<object ", at + 1)) ++objects;
  CHECK(objects == 1);
  // --unit overrides the input's.
  REQUIRE(run_offsetopt("optimize " + shell_quote(in) + " --goal volume --target-volume 20000 --quiet --unit millimeter -o " +
                            shell_quote(out),
                        dir)
              .exit_code == 0);
  CHECK(model_of(dir, out).find("<model unit=\"millimeter\"") != std::string::npos);
}
