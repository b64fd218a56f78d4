// The preview picture (issue 14): plane sections against closed-form areas (a sphere cut through
// a ring of vertices lying exactly on the plane, a torus, a sphere with a cavity), and the SVG
// rendered for real by rsvg-convert (librsvg) and decoded (tests/preview/png_to_ppm.py): the
// centre-of-mass markers sit where the model coordinates map, the shaded cavity of a
// sphere-in-sphere solid has the analytic section area π r², the picture of a run equals the
// picture of its written files, and the committed quick-start picture is what the binary draws.
#include <doctest/doctest.h>

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../support.h"
#include "../temp_dir.h"
#include "cli/write_preview.h"
#include "geometry/plane_section.h"
#include "io/json.h"
#include "mass/mass_properties.h"
#include "mesh/primitives.h"
#include "meshio/write_mesh.h"
#include "optimize/preview_svg.h"
#include "util/det_math.h"
#include "util/format_double.h"

using namespace offsetopt;
using offsetopt::cli::preview_input_from_report;
using offsetopt::test::read_file;
using offsetopt::test::RunResult;

namespace {

const TempDir& scratch() {
  static const TempDir dir("offsetopt_test_preview");
  return dir;
}

int shell(const std::string& command) {
  const int status = std::system(command.c_str());
  return offsetopt::test::exit_code_of(status);
}

RunResult run(const std::string& arguments) {
  static int counter = 0;
  const std::string err = scratch().file("err" + std::to_string(counter++) + ".txt");
  RunResult r;
  r.exit_code = shell(std::string("'") + OFFSETOPT_BINARY + "' " + arguments + " >/dev/null 2>'" + err + "'");
  r.err = read_file(err);
  return r;
}

std::string quote(const std::string& s) { return "'" + s + "'"; }

// A solid ball of radius R around `c` with a spherical cavity of radius r around `cavity`.
Mesh sphere_in_sphere(double R, const Eigen::Vector3d& c, double r, const Eigen::Vector3d& cavity, int subdivisions) {
  Mesh outer = make_icosphere(R, subdivisions), inner = make_icosphere(r, subdivisions);
  outer.V.rowwise() += c.transpose();
  inner.V.rowwise() += cavity.transpose();
  Mesh m;
  m.V.resize(outer.V.rows() + inner.V.rows(), 3);
  m.V << outer.V, inner.V;
  m.F.resize(outer.F.rows() + inner.F.rows(), 3);
  m.F.topRows(outer.F.rows()) = outer.F;
  for (Eigen::Index f = 0; f < inner.F.rows(); ++f)  // reversed: the cavity's normals point into it
    m.F.row(outer.F.rows() + f) << inner.F(f, 0) + static_cast<int>(outer.V.rows()),
        inner.F(f, 2) + static_cast<int>(outer.V.rows()), inner.F(f, 1) + static_cast<int>(outer.V.rows());
  return m;
}

// Value of attribute `name` in the element whose id is `id` (the SVG is our own, one element
// per line).
double svg_attribute(const std::string& svg, const std::string& id, const std::string& name) {
  const std::size_t element = svg.find("id=\"" + id + "\"");
  REQUIRE(element != std::string::npos);
  const std::size_t end = svg.find('>', element);
  const std::size_t at = svg.find(" " + name + "=\"", element);
  REQUIRE(at < end);
  const std::size_t start = at + name.size() + 3;
  return std::stod(svg.substr(start, svg.find('"', start) - start));
}

struct Image {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;
  Eigen::Vector3d pixel(int x, int y) const {
    const std::size_t i = 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x));
    return {double(rgb[i]), double(rgb[i + 1]), double(rgb[i + 2])};
  }
};

Image read_ppm(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string magic;
  int maxval = 0;
  Image image;
  in >> magic >> image.width >> image.height >> maxval;
  in.get();
  REQUIRE(magic == "P6");
  REQUIRE(maxval == 255);
  image.rgb.resize(3 * static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height));
  in.read(reinterpret_cast<char*>(image.rgb.data()), static_cast<std::streamsize>(image.rgb.size()));
  REQUIRE(in.good());
  return image;
}

Eigen::Vector3d hex_colour(const char* hex) {
  const unsigned long v = std::strtoul(hex + 1, nullptr, 16);
  return {double((v >> 16) & 255), double((v >> 8) & 255), double(v & 255)};
}

struct ViewBox {
  double ox, oy, s, x, y, w, h;
};

ViewBox view_box(const std::string& svg, const std::string& id) {
  return {svg_attribute(svg, id, "data-origin-x"), svg_attribute(svg, id, "data-origin-y"), svg_attribute(svg, id, "data-scale"),
          svg_attribute(svg, id, "data-x"),        svg_attribute(svg, id, "data-y"),        svg_attribute(svg, id, "data-width"),
          svg_attribute(svg, id, "data-height")};
}

// Centre of the pixels of exactly `colour` (±6 per channel) inside the view; pixel (i, j) covers
// [i, i+1] x [j, j+1]. Returns the count too.
Eigen::Vector2d colour_centroid(const Image& image, const ViewBox& v, const Eigen::Vector3d& colour, int& count) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  count = 0;
  for (int y = static_cast<int>(v.y); y < static_cast<int>(v.y + v.h); ++y)
    for (int x = static_cast<int>(v.x); x < static_cast<int>(v.x + v.w); ++x)
      if ((image.pixel(x, y) - colour).cwiseAbs().maxCoeff() <= 6.0) {
        sum += Eigen::Vector2d(x + 0.5, y + 0.5);
        ++count;
      }
  return count ? Eigen::Vector2d(sum / count) : sum;
}

bool have_renderer() {
  return shell("command -v rsvg-convert >/dev/null 2>&1") == 0 && shell("command -v python3 >/dev/null 2>&1") == 0;
}

// Renders the SVG to PNG with librsvg (1 SVG unit = 1 pixel at its default 96 dpi) and decodes it.
Image render(const std::string& svg_path) {
  const std::string png = svg_path + ".png", ppm = svg_path + ".ppm";
  REQUIRE(shell("rsvg-convert -f png -o " + quote(png) + " " + quote(svg_path)) == 0);
  REQUIRE(shell("python3 " + quote(std::string(OFFSETOPT_SOURCE_DIR) + "/tests/preview/png_to_ppm.py") + " " + quote(png) + " " +
                quote(ppm)) == 0);
  return read_ppm(ppm);
}

}  // namespace

TEST_CASE("plane_section: a sphere cut through vertices lying exactly on the plane gives one counter-clockwise loop") {
  const double R = 30.0;
  const Mesh sphere = make_icosphere(R, 4);
  int on_plane = 0;
  for (Eigen::Index i = 0; i < sphere.V.rows(); ++i) on_plane += sphere.V(i, 1) == 0.0;
  REQUIRE(on_plane > 10);  // the symbolic rule is exercised
  const PlaneSection exact = plane_section(sphere, xz_plane(0.0));
  REQUIRE(exact.status == SectionStatus::ok);
  REQUIRE(exact.loops.size() == 1);
  CHECK(exact.loops[0].closed);
  // Inscribed in the great circle: a little less than π R², and converging to it.
  const double disk = kPi * R * R;
  CHECK(exact.loops[0].signed_area < disk);
  CHECK(exact.loops[0].signed_area > 0.995 * disk);
  for (const auto& p : exact.loops[0].points) CHECK(p.norm() <= R * (1.0 + 1e-12));
  // The plane moved off the vertices by a hair: the same loop to within the move.
  const PlaneSection moved = plane_section(sphere, xz_plane(1e-9));
  REQUIRE(moved.loops.size() == 1);
  CHECK(moved.loops[0].signed_area == doctest::Approx(exact.loops[0].signed_area).epsilon(1e-8));
  // Seen from the other side (the yz plane's normal is +x) the loop is counter-clockwise as well.
  const PlaneSection side = plane_section(sphere, yz_plane(0.0));
  REQUIRE(side.loops.size() == 1);
  CHECK(side.loops[0].signed_area > 0.995 * disk);
}

TEST_CASE("plane_section: a torus cut through its equator gives an outer and an inner circle of opposite orientation") {
  const double R = 30.0, r = 10.0;
  const Mesh torus = make_torus(R, r, 96, 48);
  const double zc = 0.5 * (torus.V.col(2).minCoeff() + torus.V.col(2).maxCoeff());
  const PlaneSection section = plane_section(torus, xy_plane(zc));
  REQUIRE(section.status == SectionStatus::ok);
  REQUIRE(section.loops.size() == 2);
  double positive = 0.0, negative = 0.0;
  for (const auto& loop : section.loops) (loop.signed_area > 0 ? positive : negative) += loop.signed_area;
  CHECK(positive == doctest::Approx(kPi * (R + r) * (R + r)).epsilon(0.01));
  CHECK(negative == doctest::Approx(-kPi * (R - r) * (R - r)).epsilon(0.01));
}

TEST_CASE("plane_section: a cavity's loop runs clockwise, the material between the loops has the annulus's area") {
  const Mesh m = sphere_in_sphere(30.0, Eigen::Vector3d(0, 0, 30), 18.0, Eigen::Vector3d(6, 0, 32), 4);
  const PlaneSection section = plane_section(m, xz_plane(0.0));
  REQUIRE(section.loops.size() == 2);
  CHECK(section.loops[0].signed_area == doctest::Approx(kPi * 900.0).epsilon(0.005));
  CHECK(section.loops[1].signed_area == doctest::Approx(-kPi * 324.0).epsilon(0.005));
}

TEST_CASE("preview_svg: the same input gives the same bytes, and bad reports are refused with the field named") {
  const Mesh m = sphere_in_sphere(30.0, Eigen::Vector3d(0, 0, 30), 18.0, Eigen::Vector3d(6, 0, 32), 3);
  PreviewInput input;
  input.goal = GoalKind::volume;
  const PreviewResult a = preview_svg(m, input), b = preview_svg(m, input);
  REQUIRE(a.status == PreviewStatus::ok);
  CHECK(a.svg == b.svg);
  CHECK(a.svg.find("<script") == std::string::npos);
  CHECK(a.svg.find("href") == std::string::npos);
  CHECK(a.svg.find("@import") == std::string::npos);

  PreviewInput parsed;
  CHECK(preview_input_from_report(Json::parse("{}"), parsed).find("parameters") != std::string::npos);
  CHECK(preview_input_from_report(Json::parse(R"({"parameters": {"goal": "fly"}})"), parsed).find("fly") != std::string::npos);
  CHECK(preview_input_from_report(Json::parse(R"({"parameters": {"goal": "float"}})"), parsed).find("fluid_density") !=
        std::string::npos);
  CHECK(preview_input_from_report(Json::parse(R"({"parameters": {"goal": "stand"}, "before": {"center_of_mass": [1, 2]}})"),
                                  parsed)
            .find("before.center_of_mass") != std::string::npos);
  REQUIRE(preview_input_from_report(
              Json::parse(R"({"parameters": {"goal": "roly-poly", "margin": 0.5, "ground_tol": null},
                              "goal": {"sphere_center": [0, 0, 30], "sphere_radius": 30},
                              "before": {"center_of_mass": [1, 2, 3]}})"),
              parsed)
              .empty());
  CHECK(parsed.goal == GoalKind::roly_poly);
  CHECK(parsed.margin == 0.5);
  CHECK(parsed.ground_tol < 0.0);
  CHECK(parsed.has_sphere);
  CHECK(parsed.sphere_radius == 30.0);
  CHECK(parsed.before_com == Eigen::Vector3d(1, 2, 3));
}

// The number printed right after `label` in the SVG's text.
double number_after(const std::string& svg, const std::string& label) {
  const std::size_t at = svg.find(label);
  REQUIRE_MESSAGE(at != std::string::npos, label);
  return std::stod(svg.substr(at + label.size(), 40));
}

TEST_CASE("preview_svg: the goals' figures agree with closed forms (tipping angle, waterline, moments, void)") {
  SUBCASE("stand: a 20 x 10 x 20 box tips over its long edge at atan(5 / 10)") {
    const Mesh box = make_box(Eigen::Vector3d(-10, -5, 0), Eigen::Vector3d(10, 5, 20));
    PreviewInput input;
    input.goal = GoalKind::stand;
    input.margin = 1.0;
    const PreviewResult r = preview_svg(box, input);
    REQUIRE(r.status == PreviewStatus::ok);
    CHECK(number_after(r.svg, "tipping angle ") == doctest::Approx(std::atan(0.5) * 180.0 / kPi).epsilon(1e-3));
    CHECK(number_after(r.svg, "centre of mass inside it by ") == doctest::Approx(5.0).epsilon(1e-3));
  }
  const double R = 30.0, r = 18.0;
  const Eigen::Vector3d centre(0, 0, 30);
  const Mesh ball = sphere_in_sphere(R, centre, r, centre, 5);
  const Vector10d P = mass_properties(ball);
  SUBCASE("float: a concentric shell in fluid of density m / (V_out / 2) floats with the waterline through its centre") {
    const Mesh outer = make_icosphere(R, 5);
    const double v_out = mass_properties(outer)(kMass);
    PreviewInput input;
    input.goal = GoalKind::floating;
    input.fluid_density = P(kMass) / (0.5 * v_out);
    const PreviewResult res = preview_svg(ball, input);
    REQUIRE(res.status == PreviewStatus::ok);
    CHECK(number_after(res.svg, "waterline z = ") == doctest::Approx(30.0).epsilon(1e-3));
    // Centre of buoyancy of a half ball: 3R/8 below the centre.
    const std::string cob = "centre of buoyancy (";
    const std::size_t at = res.svg.find(cob);
    REQUIRE(at != std::string::npos);
    const double z = std::stod(res.svg.substr(res.svg.find(", ", res.svg.find(", ", at) + 2) + 2, 20));
    CHECK(z == doctest::Approx(30.0 - 3.0 * R / 8.0).epsilon(2e-3));
  }
  SUBCASE("spin: Izz of a concentric shell is 8 pi (R^5 - r^5) / 15; volume: the void is 4 pi r^3 / 3") {
    PreviewInput input;
    input.goal = GoalKind::spin;
    input.has_tip = true;
    input.tip = Eigen::Vector3d(0, 0, 0);
    const PreviewResult res = preview_svg(ball, input);
    REQUIRE(res.status == PreviewStatus::ok);
    const double izz = 8.0 * kPi * (std::pow(R, 5) - std::pow(r, 5)) / 15.0;
    CHECK(number_after(res.svg, "Izz ") == doctest::Approx(izz).epsilon(3e-3));  // icosphere vs sphere
    CHECK(res.svg.find(">Izz</text>") != std::string::npos);                     // the bar chart
    input.goal = GoalKind::volume;
    const PreviewResult vol = preview_svg(ball, input);
    CHECK(number_after(vol.svg, "void volume ") == doctest::Approx(4.0 * kPi * r * r * r / 3.0).epsilon(3e-3));
  }
}

TEST_CASE("preview renders: markers where the coordinates map, the cavity's shaded area is pi r^2") {
  INFO("scripts/deps.sh installs rsvg-convert (Debian librsvg2-bin) and python3");
  REQUIRE(have_renderer());
  const double R = 30.0, r = 18.0;
  const Eigen::Vector3d centre(0, 0, 30), cavity(6, 0, 32);
  const Mesh m = sphere_in_sphere(R, centre, r, cavity, 5);
  const std::string solid = scratch().file("ball.ply"), report = scratch().file("ball.json"), svg = scratch().file("ball.svg");
  write_mesh(solid, m);
  const Vector10d P = mass_properties(m);
  const Eigen::Vector3d com(P(kCx), P(kCy), P(kCz)), before(-14.0, 9.0, 45.0);
  // The shell's centre of mass, analytically: the ball minus the cavity.
  const Eigen::Vector3d analytic = (R * R * R * centre - r * r * r * cavity) / (R * R * R - r * r * r);
  REQUIRE((com - analytic).norm() < 0.05);
  Json j = Json::object();
  Json parameters = Json::object();
  parameters["goal"] = "volume";
  parameters["margin"] = 0.5;
  parameters["target_volume"] = 20000.0;
  j["parameters"] = parameters;
  Json b = Json::object();
  b["center_of_mass"] = Json::array_of({before.x(), before.y(), before.z()});
  j["before"] = b;
  {
    std::ofstream out(report, std::ios::binary);
    out << j.dump(2);
  }
  const RunResult result = run("preview " + quote(solid) + " --report " + quote(report) + " -o " + quote(svg));
  REQUIRE(result.exit_code == 0);
  CHECK(result.err.empty());
  const std::string text = read_file(svg);
  const Image image = render(svg);

  // Each view: after and before markers within 1 px of where the coordinates map.
  struct Case {
    const char* id;
    int u, v;  // coordinate indices
  };
  for (const Case c : {Case{"view-xz", 0, 2}, Case{"view-yz", 1, 2}, Case{"view-top", 0, 1}}) {
    CAPTURE(c.id);
    const ViewBox v = view_box(text, c.id);
    CHECK(v.x + v.w <= image.width);
    CHECK(v.y + v.h <= image.height);
    for (const auto& [colour, point] : {std::pair<const char*, Eigen::Vector3d>{kPreviewComAfterColour, com},
                                        std::pair<const char*, Eigen::Vector3d>{kPreviewComBeforeColour, before}}) {
      CAPTURE(colour);
      int count = 0;
      const Eigen::Vector2d found = colour_centroid(image, v, hex_colour(colour), count);
      CHECK(count >= 20);  // a disc of radius ~4 px, not a stray pixel
      const Eigen::Vector2d expected(v.ox + v.s * point(c.u), v.oy - v.s * point(c.v));
      MESSAGE(std::string(c.id) << " " << std::string(colour) << ": " << count << " pixels, centre " << (found - expected).norm() << " px from the mapped point");
      CHECK((found - expected).norm() < 1.0);
    }
  }

  // The xz section at y = cy (= 0 up to rounding) cuts both spheres through their centres.
  // Coverage per pixel: where the pixel lies on the segment between the material colour and the
  // cavity colour (anti-aliased edges count by fraction); anything far from that segment (white,
  // outlines, markers) counts as neither.
  const ViewBox v = view_box(text, "view-xz");
  const Eigen::Vector3d M = hex_colour(kPreviewMaterialColour), C = hex_colour(kPreviewCavityColour);
  double cavity_px = 0.0, section_px = 0.0;
  Eigen::Vector2d cavity_moment = Eigen::Vector2d::Zero();
  for (int y = static_cast<int>(v.y) + 1; y < static_cast<int>(v.y + v.h) - 1; ++y)
    for (int x = static_cast<int>(v.x) + 1; x < static_cast<int>(v.x + v.w) - 1; ++x) {
      const Eigen::Vector3d p = image.pixel(x, y);
      const double t = (p - M).dot(C - M) / (C - M).squaredNorm();
      if (t < -0.05 || t > 1.05 || (p - (M + t * (C - M))).norm() > 12.0) continue;
      const double tc = std::min(std::max(t, 0.0), 1.0);
      cavity_px += tc;
      cavity_moment += tc * Eigen::Vector2d(x + 0.5, y + 0.5);
      section_px += 1.0;
    }
  const double scale2 = v.s * v.s;
  MESSAGE("cavity area " << cavity_px / scale2 << " vs pi r^2 = " << kPi * r * r << "; section (material + cavity) "
                         << section_px / scale2 << " vs pi R^2 = " << kPi * R * R << "; scale " << v.s << " px per unit");
  CHECK(cavity_px / scale2 == doctest::Approx(kPi * r * r).epsilon(0.02));
  // The mapping itself, from geometry alone: the yellow disc is centred where the cavity's
  // centre maps.
  const Eigen::Vector2d cavity_centre = cavity_moment / cavity_px;
  const Eigen::Vector2d mapped(v.ox + v.s * cavity.x(), v.oy - v.s * cavity.z());
  MESSAGE("cavity disc centred " << (cavity_centre - mapped).norm() << " px from where (6, 32) maps");
  CHECK((cavity_centre - mapped).norm() < 1.0);
  // The whole disk (the outline's 1 px stroke on the outer circle takes a sliver).
  CHECK(section_px / scale2 == doctest::Approx(kPi * R * R).epsilon(0.03));
}

TEST_CASE("optimize --preview draws the same bytes as preview of the written solid and report, and bad usage exits 2") {
  const std::string source = OFFSETOPT_SOURCE_DIR;
  const std::string solid = scratch().file("s.ply"), report = scratch().file("s.json"), a = scratch().file("a.svg"),
                    b = scratch().file("b.svg");
  const RunResult opt = run("optimize " + quote(source + "/meshes/sphere.obj") +
                            " --goal volume --target-volume 20000 --quiet --no-timings -o " + quote(solid) + " --report " +
                            quote(report) + " --preview " + quote(a));
  REQUIRE(opt.exit_code == 0);
  REQUIRE(run("preview " + quote(solid) + " --report " + quote(report) + " -o " + quote(b)).exit_code == 0);
  const std::string svg = read_file(a);
  REQUIRE(!svg.empty());
  CHECK(svg == read_file(b));
  CHECK(svg.find("void volume") != std::string::npos);
  // A welded solid with an opening, written as OBJ: the file read back drops the vertices no
  // face uses, the picture leaves them out in memory too. (`--cavity offset` writes the offset
  // surfaces welded along the region; it exits 3: the wall next to the opening's rim is thinner
  // than requested; outputs are written all the same.)
  const std::string open_solid = scratch().file("open.obj"), open_report = scratch().file("open.json"),
                    c = scratch().file("c.svg"), d = scratch().file("d.svg");
  REQUIRE(run("optimize " + quote(source + "/meshes/bottle.obj") + " --goal stand --fix 'z>240' --cavity offset --quiet --no-timings -o " +
              quote(open_solid) + " --report " + quote(open_report) + " --preview " + quote(c))
              .exit_code == 3);
  REQUIRE(run("preview " + quote(open_solid) + " --report " + quote(open_report) + " -o " + quote(d)).exit_code == 0);
  CHECK(!read_file(c).empty());
  CHECK(read_file(c) == read_file(d));

  const std::string bad_json = scratch().file("bad.json"), empty_json = scratch().file("empty.json");
  {
    std::ofstream(bad_json) << "{\"parameters\": ";
    std::ofstream(empty_json) << "{\"goal\": {}}";
  }
  for (const std::string& arguments :
       {"preview " + quote(solid) + " -o " + quote(scratch().file("x.svg")),
        "preview " + quote(solid) + " --report " + quote(report),
        "preview " + quote(solid) + " --report " + quote(bad_json) + " -o " + quote(scratch().file("x.svg")),
        "preview " + quote(solid) + " --report " + quote(empty_json) + " -o " + quote(scratch().file("x.svg")),
        "preview " + quote(solid) + " --report " + quote(scratch().file("none.json")) + " -o " + quote(scratch().file("x.svg")),
        "preview " + quote(solid) + " --report " + quote(report) + " -o " + quote(report),
        "preview " + quote(solid) + " --report " + quote(report) + " --bogus -o x.svg", std::string("preview")}) {
    CAPTURE(arguments);
    const RunResult r = run(arguments);
    CHECK(r.exit_code == 2);
    CHECK(r.err.rfind("Error: ", 0) == 0);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  }
  CHECK(read_file(report).find("\"parameters\"") != std::string::npos);  // not overwritten
}

TEST_CASE("the quick-start picture meshes/bottle-stand-preview.svg is what optimize --preview draws for the demo bottle") {
  // Regenerate with tests/golden/regenerate.sh (or the README's first command with
  // --preview meshes/bottle-stand-preview.svg). The picture quotes the optimised solid, which is
  // exact only for the build the golden files were written with (tests/golden/BUILD.txt).
  const std::string source = OFFSETOPT_SOURCE_DIR;
  const std::string svg = scratch().file("bottle.svg"), version = scratch().file("version.txt");
  REQUIRE(shell(std::string("'") + OFFSETOPT_BINARY + "' --version > '" + version + "'") == 0);
  if (read_file(version) != read_file(source + "/tests/golden/BUILD.txt")) {
    offsetopt::test::skip_test("another build than tests/golden/BUILD.txt: the picture is compared only on that build");
    return;
  }
  const RunResult r = run("optimize " + quote(source + "/meshes/bottle.obj") + " --goal stand --no-timings -o " +
                          quote(scratch().file("bottle.ply")) + " --preview " + quote(svg));
  REQUIRE(r.exit_code == 0);
  const std::string committed = read_file(source + "/meshes/bottle-stand-preview.svg");
  REQUIRE(!committed.empty());
  CHECK(read_file(svg) == committed);
}
