// --up, --pose stable and --flatten through the real binary (issue 13): a y-up copy of the demo
// bottle run with --up y gives the z-up run's meshes (solid, inner, outer, skeleton) byte for byte
// once turned back, and the same report apart from the input's name and the pose; a tilted box
// posed stable rests on its largest face with the analytic margin; a flattened sphere's written
// surface passes `check`; a sheared prism that `--up +x` stands on its end is refused, and every
// pose remedy the refusal names, run as typed, stands.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "../support.h"
#include "../temp_dir.h"
#include "geometry/pose.h"
#include "io/json.h"
#include "mesh/demo_meshes.h"
#include "mesh/primitives.h"
#include "meshio/load_mesh.h"
#include "meshio/read_raw_mesh.h"
#include "meshio/write_mesh.h"
#include "util/det_math.h"

using namespace offsetopt;
using offsetopt::test::read_file;

namespace {

const std::string kBinary = OFFSETOPT_BINARY;

const TempDir& temp() {
  static const TempDir dir("offsetopt-poses");
  return dir;
}

int run(const std::string& command) {
  const int status = std::system(("timeout 300 " + command + " 2>>" + temp().file("stderr.txt")).c_str());
  REQUIRE(status != -1);
  return offsetopt::test::exit_code_of(status);
}

// The report without the keys that name files or the pose (those differ between the runs).
std::string comparable(const Json& report) {
  Json out = Json::object();
  for (const auto& item : report.items())
    if (item.first != "input" && item.first != "pose" && item.first != "outputs") out.set(item.first, item.second);
  return out.dump(2);
}

}  // namespace

TEST_CASE("--up y on a y-up copy of the bottle equals the z-up run, byte for byte after turning back") {
  const Mesh bottle = make_demo_mesh("bottle");
  AxisPermutation up_y;
  REQUIRE(up_axis_permutation("+y", up_y));
  const std::string z_up = temp().file("bottle_z.obj"), y_up = temp().file("bottle_y.obj");
  write_mesh(z_up, bottle);
  write_mesh(y_up, permute_axes(bottle, up_y.inverse()));
  const std::string outputs = " --goal stand --quiet --no-timings";
  auto files = [&](const std::string& tag) {
    return " -o " + temp().file(tag + ".obj") + " --inner " + temp().file(tag + "_inner.obj") + " --outer-mesh " +
           temp().file(tag + "_outer.obj") + " --skeleton " + temp().file(tag + "_skeleton.obj") + " --report " +
           temp().file(tag + ".json");
  };
  const int code_z = run(kBinary + " optimize " + z_up + outputs + files("z"));
  const int code_y = run(kBinary + " optimize " + y_up + " --up y" + outputs + files("y"));
  CHECK(code_z == 0);
  CHECK(code_z == code_y);
  for (const std::string suffix : {"", "_inner", "_outer", "_skeleton"}) {
    CAPTURE(suffix);
    // Read as written (the skeleton is no valid solid, so not through load_mesh's checks).
    const RawMesh raw = read_raw_mesh(temp().file("z" + suffix + ".obj"));
    Mesh written_z;
    written_z.V = raw.V;
    written_z.F = raw.F;
    const std::string bytes_y = read_file(temp().file("y" + suffix + ".obj"));
    REQUIRE_FALSE(bytes_y.empty());
    CHECK(mesh_to_bytes(".obj", permute_axes(written_z, up_y.inverse())) == bytes_y);
  }
  const Json report_z = Json::parse(read_file(temp().file("z.json")));
  const Json report_y = Json::parse(read_file(temp().file("y.json")));
  CHECK(comparable(report_z) == comparable(report_y));
  CHECK_FALSE(report_z.contains("pose"));
  CHECK(report_y.at("pose").at("output_frame").as_string() == "input");
  CHECK(report_y.at("pose").at("rotation").at(1).at(2).as_number() == -1.0);  // y' = −z

  // inspect sees the same solid.
  REQUIRE(run(kBinary + " inspect " + z_up + " --json " + temp().file("iz.json")) == 0);
  REQUIRE(run(kBinary + " inspect " + y_up + " --up +y --json " + temp().file("iy.json")) == 0);
  CHECK(comparable(Json::parse(read_file(temp().file("iz.json")))) == comparable(Json::parse(read_file(temp().file("iy.json")))));
}

TEST_CASE("inspect --pose stable: a tilted box rests on its largest face with margin 1") {
  Mesh box = make_box(Eigen::Vector3d(-2, -1, -0.5), Eigen::Vector3d(2, 1, 0.5));
  double s, c;
  det_sincos(0.5, s, c);
  for (Eigen::Index i = 0; i < box.V.rows(); ++i) {  // tilted about x, then about z
    const double y = box.V(i, 1), z = box.V(i, 2);
    box.V(i, 1) = c * y - s * z;
    box.V(i, 2) = s * y + c * z;
    const double x = box.V(i, 0), y2 = box.V(i, 1);
    box.V(i, 0) = c * x - s * y2;
    box.V(i, 1) = s * x + c * y2;
  }
  const std::string path = temp().file("tilted_box.obj");
  write_mesh(path, box);
  REQUIRE(run(kBinary + " inspect " + path + " --json " + temp().file("box_as_is.json")) == 0);
  const Json as_is = Json::parse(read_file(temp().file("box_as_is.json")));
  CHECK(as_is.at("stability").at("contact_vertices").as_integer() == 2);  // on an edge
  CHECK_FALSE(as_is.at("stability").at("stands").as_bool());
  REQUIRE(run(kBinary + " inspect " + path + " --pose stable --json " + temp().file("box.json")) == 0);
  const Json report = Json::parse(read_file(temp().file("box.json")));
  CHECK(report.at("pose").at("stable").at("margin").as_number() == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(report.at("pose").at("stable").at("facet_area").as_number() == doctest::Approx(8.0).epsilon(1e-12));
  CHECK(report.at("pose").at("output_frame").as_string() == "posed");
  CHECK(report.at("bbox").at("min").at(2).as_number() == 0.0);
  CHECK(report.at("bbox").at("max").at(2).as_number() == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(report.at("stability").at("contact_vertices").as_integer() == 4);
  CHECK(report.at("stability").at("com_margin").as_number() == doctest::Approx(1.0).epsilon(1e-9));
  CHECK(run(kBinary + " inspect " + path + " --pose sideways") == 2);
  CHECK(run(kBinary + " inspect " + path + " --up w") == 2);
}

TEST_CASE("optimize --flatten on a sphere: the written surface is a closed solid with a flat base") {
  const std::string path = temp().file("sphere.obj");
  write_mesh(path, make_icosphere(30.0, 3));
  const std::string outer = temp().file("sphere_outer.obj");
  const int code = run(kBinary + " optimize " + path + " --flatten 5 --goal stand --quiet --no-timings -o " +
                       temp().file("sphere_solid.obj") + " --outer-mesh " + outer + " --report " + temp().file("sphere.json"));
  CHECK(code == 0);
  CHECK(run(kBinary + " check " + outer + " >/dev/null") == 0);
  const Json report = Json::parse(read_file(temp().file("sphere.json")));
  const Json& flatten = report.at("pose").at("flatten");
  CHECK(flatten.at("height").as_number() == 5.0);
  CHECK(flatten.at("cap_loops").as_integer() == 1);
  const Mesh written = load_mesh(outer).mesh;
  CHECK(written.V.col(2).minCoeff() == flatten.at("plane_z").as_number());
  CHECK(written.V.rows() == flatten.at("vertices").as_integer());
  // --flatten larger than the object, or not a positive number: exit 2, nothing written.
  CHECK(run(kBinary + " optimize " + path + " --flatten 60 --goal stand --quiet -o " + temp().file("none.obj")) == 2);
  CHECK(run(kBinary + " optimize " + path + " --flatten -1 --goal stand --quiet -o " + temp().file("none.obj")) == 2);
  CHECK(read_file(temp().file("none.obj")).empty());
}

// A square prism 2 × 2 × 10 standing on its end, sheared y += 0.8 z: no void brings its centre of
// mass over the end, and it stands on either flat side whose normal is ±x. The file holds it
// turned so that `--up +x` poses it on its end. Every pose remedy the refusal names is run as the
// user would type it, and stands; before, the remedies named the posed mesh's axes ("--up +x" for
// the side that is the file's -z), which is not what the file needs.
TEST_CASE("optimize --up +x: every pose remedy of a refusal names the file's axis, and stands as typed") {
  Mesh prism = make_cylinder(std::sqrt(2.0), 0.0, 10.0, 4, 20, 3);
  double s, c;
  det_sincos(0.25 * kPi, s, c);
  for (Eigen::Index i = 0; i < prism.V.rows(); ++i) {
    const double x = prism.V(i, 0), y = prism.V(i, 1);
    prism.V(i, 0) = c * x - s * y;
    prism.V(i, 1) = s * x + c * y + 0.8 * prism.V(i, 2);
  }
  AxisPermutation up_x;
  REQUIRE(up_axis_permutation("+x", up_x));
  const std::string path = temp().file("sheared_prism.obj");
  write_mesh(path, permute_axes(prism, up_x.inverse()));
  const std::string report_path = temp().file("sheared_prism.json");
  REQUIRE(run(kBinary + " optimize " + path + " --goal stand --up +x --quiet -o " + temp().file("sheared.stl") +
              " --report " + report_path) == 3);
  const Json report = Json::parse(read_file(report_path));
  const Json& reach = report.at("reachability");
  CHECK(reach.at("decided").as_bool());
  CHECK_FALSE(reach.at("reachable").as_bool());
  int named = 0;
  bool plus_z = false, minus_z = false;
  for (const Json& remedy : reach.at("remedies").elements()) {
    const std::string option = remedy.at("option").as_string();
    CAPTURE(option);
    CHECK(option != "--up +x");  // the pose it has
    if (!remedy.at("reachable").as_bool() || option.rfind("--flatten", 0) == 0 || option == "--outer") continue;
    ++named;
    plus_z = plus_z || option == "--up +z";
    minus_z = minus_z || option == "--up -z";
    // As typed: an --up replaces the user's, --pose stable joins it.
    const std::string pose = option.rfind("--up ", 0) == 0 ? option : "--up +x " + option;
    CHECK(run(kBinary + " optimize " + path + " --goal stand " + pose + " --quiet -o " + temp().file("remedy.stl")) == 0);
  }
  // The two flat sides are the file's +z and -z (the turned mesh's ±x).
  CHECK(plus_z);
  CHECK(minus_z);
  CHECK(named >= 2);
}
