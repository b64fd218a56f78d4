// --flatten (issue 13): the cut-and-cap of flatten_base against independent computations: the cap
// area against the shoelace area of the edge/plane intersection points (ordered by angle here,
// not by the library's loop chaining) and against π r² of the analytic circle; the volume against
// the original volume minus the part below the plane (triangles clipped here, summed as cones
// from a point on the plane); validity as `check` sees it; a ring section (one hole), a section
// of two pieces, a plane through a ring of vertices (the symbolic rule), and the demo meshes cut
// at many heights.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "geometry/flatten_base.h"
#include "geometry/pose.h"
#include "mass/stable_pose.h"
#include "geometry/triangulate_polygons.h"
#include "mass/mass_properties.h"
#include "mass/volume_integrals.h"
#include "mesh/demo_meshes.h"
#include "mesh/primitives.h"
#include "meshio/validate_mesh.h"
#include "util/det_math.h"

using namespace offsetopt;

namespace {

// Intersection points of the mesh's edges with z = plane, each from its upper end (the library
// interpolates from the lower one).
std::vector<Eigen::Vector2d> cut_points(const Mesh& mesh, double plane) {
  std::set<std::pair<int, int>> edges;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
      edges.emplace(std::min(a, b), std::max(a, b));
    }
  std::vector<Eigen::Vector2d> points;
  for (const auto& [a, b] : edges) {
    Eigen::Vector3d p = mesh.V.row(a).transpose(), q = mesh.V.row(b).transpose();
    if ((p.z() < plane) == (q.z() < plane)) continue;
    if (p.z() < q.z()) std::swap(p, q);
    const Eigen::Vector3d x = p + (plane - p.z()) / (q.z() - p.z()) * (q - p);
    points.emplace_back(x.x(), x.y());
  }
  return points;
}

// Shoelace area of points ordered by angle about `center` (a star-shaped polygon).
double star_area(std::vector<Eigen::Vector2d> points, const Eigen::Vector2d& center) {
  std::sort(points.begin(), points.end(), [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return std::atan2(a.y() - center.y(), a.x() - center.x()) < std::atan2(b.y() - center.y(), b.x() - center.x());
  });
  return 0.5 * twice_signed_area(points);
}

// Volume of the solid below z = plane: each triangle clipped to z < plane, as cones from a point
// on the plane (the missing cap lies in the plane and adds nothing).
double volume_below(const Mesh& mesh, double plane) {
  const Eigen::Vector3d o(0, 0, plane);
  double volume = 0.0;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    std::vector<Eigen::Vector3d> kept;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = mesh.V.row(mesh.F(f, k)).transpose(), q = mesh.V.row(mesh.F(f, (k + 1) % 3)).transpose();
      if (p.z() < plane) kept.push_back(p);
      if ((p.z() < plane) != (q.z() < plane)) kept.push_back(p + (plane - p.z()) / (q.z() - p.z()) * (q - p));
    }
    for (std::size_t i = 1; i + 1 < kept.size(); ++i)
      volume += (kept[0] - o).dot((kept[i] - o).cross(kept[i + 1] - o)) / 6.0;
  }
  return volume;
}

struct CapFigures {
  double area = 0.0;
  bool faces_down = true, in_plane = true;
};

CapFigures cap_figures(const FlattenResult& r) {
  CapFigures c;
  for (Eigen::Index f = r.mesh.F.rows() - r.cap_faces; f < r.mesh.F.rows(); ++f) {
    const Eigen::Vector3d a = r.mesh.V.row(r.mesh.F(f, 0)).transpose(), b = r.mesh.V.row(r.mesh.F(f, 1)).transpose(),
                          d = r.mesh.V.row(r.mesh.F(f, 2)).transpose();
    const Eigen::Vector3d n = (b - a).cross(d - a);
    c.area += 0.5 * n.norm();
    if (!(n.z() < 0.0)) c.faces_down = false;
    if (a.z() != r.plane_z || b.z() != r.plane_z || d.z() != r.plane_z) c.in_plane = false;
  }
  return c;
}

double volume_of(const Mesh& mesh) { return volume_integrals(mesh).values(kIntVolume); }

}  // namespace

TEST_CASE("flatten_base: a sphere gets a closed base disk of the cut polygon's area") {
  const double radius = 30.0;
  const Mesh sphere = make_icosphere(radius, 4);
  const FlattenResult r = flatten_base(sphere, FlattenOptions{5.0});
  REQUIRE(r.status == FlattenStatus::ok);
  const double plane = sphere.V.col(2).minCoeff() + 5.0;
  CHECK(r.plane_z == plane);
  CHECK(r.cap_loops == 1);
  CHECK(r.cap_holes == 0);
  CHECK(validate_mesh(r.mesh).valid());
  CHECK(r.mesh.V.col(2).minCoeff() == plane);
  const CapFigures cap = cap_figures(r);
  CHECK(cap.faces_down);
  CHECK(cap.in_plane);
  const std::vector<Eigen::Vector2d> points = cut_points(sphere, plane);
  CHECK(static_cast<int>(points.size()) == r.cut_edges);
  const double shoelace = star_area(points, Eigen::Vector2d(0, 0));
  CHECK(cap.area == doctest::Approx(shoelace).epsilon(1e-9));
  const double circle = kPi * (radius * radius - plane * plane);
  CHECK(cap.area == doctest::Approx(circle).epsilon(0.01));  // the polygon is inscribed: a bit less
  CHECK(cap.area < circle);
  const double removed = volume_below(sphere, plane);
  CHECK(removed > 0.0);
  CHECK(volume_of(r.mesh) == doctest::Approx(volume_of(sphere) - removed).epsilon(1e-12));
  // The analytic spherical cap below the plane, within the mesh's discretisation.
  const double h = radius + plane;
  CHECK(removed == doctest::Approx(kPi * h * h * (3 * radius - h) / 3.0).epsilon(0.03));
}

TEST_CASE("flatten_base: a torus lying flat cut through its tube gives a ring cap (one hole)") {
  const Mesh torus = make_torus(30.0, 10.0, 64, 24);
  const FlattenResult r = flatten_base(torus, FlattenOptions{4.0});
  REQUIRE(r.status == FlattenStatus::ok);
  CHECK(r.snapped_vertices == 0);
  CHECK(r.cap_loops == 2);
  CHECK(r.cap_holes == 1);
  CHECK(validate_mesh(r.mesh).valid());
  const CapFigures cap = cap_figures(r);
  CHECK(cap.faces_down);
  CHECK(cap.in_plane);
  const double plane = r.plane_z;
  std::vector<Eigen::Vector2d> outer, inner;
  for (const auto& p : cut_points(torus, plane)) (p.norm() > 30.0 ? outer : inner).push_back(p);
  const double shoelace = star_area(outer, Eigen::Vector2d(0, 0)) - star_area(inner, Eigen::Vector2d(0, 0));
  CHECK(cap.area == doctest::Approx(shoelace).epsilon(1e-9));
  const double depth = plane - torus.V.col(2).minCoeff();
  const double half_chord = std::sqrt(100.0 - (10.0 - depth) * (10.0 - depth));
  const double annulus = kPi * ((30.0 + half_chord) * (30.0 + half_chord) - (30.0 - half_chord) * (30.0 - half_chord));
  CHECK(cap.area == doctest::Approx(annulus).epsilon(0.03));
  CHECK(volume_of(r.mesh) == doctest::Approx(volume_of(torus) - volume_below(torus, plane)).epsilon(1e-12));

  // At H = 5 the plane passes within rounding of two rings of tube vertices (10 sin 210° = 10 sin 330° = −5):
  // they are put on it, and no sliver is left.
  const FlattenResult near = flatten_base(torus, FlattenOptions{5.0});
  REQUIRE(near.status == FlattenStatus::ok);
  CHECK(near.snapped_vertices == 128);  // the rings at 210° and 330°
  CHECK(near.cap_holes == 1);
  CHECK(validate_mesh(near.mesh).valid());
  CHECK(cap_figures(near).faces_down);
}

TEST_CASE("flatten_base: a torus standing on its side cut above its hole gives two base pieces") {
  Mesh torus = make_torus(30.0, 10.0, 64, 24);
  for (Eigen::Index i = 0; i < torus.V.rows(); ++i) {  // axis along y: (x, y, z) -> (x, −z, y)
    const double y = torus.V(i, 1), z = torus.V(i, 2);
    torus.V(i, 1) = -z;
    torus.V(i, 2) = y;
  }
  const FlattenResult r = flatten_base(torus, FlattenOptions{25.0});
  REQUIRE(r.status == FlattenStatus::ok);
  CHECK(r.cap_loops == 2);
  CHECK(r.cap_holes == 0);
  CHECK(validate_mesh(r.mesh).valid());
  const CapFigures cap = cap_figures(r);
  CHECK(cap.faces_down);
  std::vector<Eigen::Vector2d> left, right;
  for (const auto& p : cut_points(torus, r.plane_z)) (p.x() < 0 ? left : right).push_back(p);
  double centre_left = 0, centre_right = 0;
  for (const auto& p : left) centre_left += p.x() / left.size();
  for (const auto& p : right) centre_right += p.x() / right.size();
  const double shoelace = star_area(left, Eigen::Vector2d(centre_left, 0)) + star_area(right, Eigen::Vector2d(centre_right, 0));
  CHECK(cap.area == doctest::Approx(shoelace).epsilon(1e-9));
  CHECK(volume_of(r.mesh) == doctest::Approx(volume_of(torus) - volume_below(torus, r.plane_z)).epsilon(1e-12));

  // Tangent to the top of the hole (z = 20, a saddle vertex on the plane): the two pieces of the
  // section touch at that vertex, the solid above does not pinch, and the cut is a valid solid.
  const FlattenResult top = flatten_base(torus, FlattenOptions{60.0});
  REQUIRE(top.status == FlattenStatus::ok);
  CHECK(top.cap_loops == 2);
  CHECK(validate_mesh(top.mesh).valid());
  CHECK(cap_figures(top).faces_down);
  // Tangent to the bottom of the hole (z = −20): what is left above pinches at that vertex (two
  // parts touching in a point), which validation names; pose_input refuses it with that message.
  const FlattenResult bottom = flatten_base(torus, FlattenOptions{20.0});
  REQUIRE(bottom.status == FlattenStatus::ok);
  CHECK(validate_mesh(bottom.mesh).find(DefectKind::non_manifold_vertex) != nullptr);
}

TEST_CASE("flatten_base: a plane through a ring of vertices cuts at them, bad heights are refused") {
  const int segments = 32;
  const Mesh cylinder = make_cylinder(10.0, 0.0, 10.0, segments, 4, 3);
  int on_plane = 0;
  for (Eigen::Index i = 0; i < cylinder.V.rows(); ++i) on_plane += cylinder.V(i, 2) == 5.0;
  REQUIRE(on_plane == segments);
  const FlattenResult r = flatten_base(cylinder, FlattenOptions{5.0});
  REQUIRE(r.status == FlattenStatus::ok);
  CHECK(r.plane_z == 5.0);
  CHECK(r.mesh.V.col(2).minCoeff() == 5.0);
  CHECK(r.cut_edges == segments);  // the ring itself: no new point
  CHECK(r.mesh.V.rows() == cylinder.V.rows() - r.removed_vertices);
  CHECK(validate_mesh(r.mesh).valid());
  CHECK(cap_figures(r).faces_down);
  CHECK(volume_of(r.mesh) == doctest::Approx(volume_of(cylinder) - volume_below(cylinder, 5.0)).epsilon(1e-12));
  CHECK(volume_of(r.mesh) == doctest::Approx(volume_of(cylinder) / 2).epsilon(1e-12));

  // The cylinder tilted a little: the plane passes through one vertex of a ring and crosses
  // edges everywhere else.
  Mesh tilted = cylinder;
  for (Eigen::Index i = 0; i < tilted.V.rows(); ++i) tilted.V(i, 2) += 0.0625 * tilted.V(i, 0);
  const double zmin = tilted.V.col(2).minCoeff();
  double through = 0.0;  // the height of the ring-2 vertex at angle 0: x = 10
  for (Eigen::Index i = 0; i < tilted.V.rows(); ++i)
    if (cylinder.V(i, 2) == 5.0 && cylinder.V(i, 0) == 10.0) through = tilted.V(i, 2);
  REQUIRE(through == 5.625);
  const FlattenResult t = flatten_base(tilted, FlattenOptions{through - zmin});
  REQUIRE(t.status == FlattenStatus::ok);
  REQUIRE(t.plane_z == through);
  CHECK(validate_mesh(t.mesh).valid());
  CHECK(cap_figures(t).faces_down);
  CHECK(volume_of(t.mesh) == doctest::Approx(volume_of(tilted) - volume_below(tilted, t.plane_z)).epsilon(1e-12));

  CHECK(flatten_base(cylinder, FlattenOptions{10.0}).status == FlattenStatus::cuts_everything);
  CHECK(flatten_base(cylinder, FlattenOptions{0.0}).status == FlattenStatus::bad_options);
  CHECK(flatten_base(cylinder, FlattenOptions{std::nan("")}).status == FlattenStatus::bad_options);
}

TEST_CASE("triangulate_polygons: a square with two square holes uses every point, area exact") {
  const std::vector<std::vector<Eigen::Vector2d>> loops = {
      {{0, 0}, {10, 0}, {10, 10}, {0, 10}},
      {{2, 2}, {2, 4}, {4, 4}, {4, 2}},          // clockwise: a hole
      {{6, 6}, {6, 8}, {8, 8}, {8, 6}},          // a second hole
      {{2.5, 2.5}, {3.5, 2.5}, {3.5, 3.5}},      // an island inside the first hole
  };
  const PolygonTriangulation t = triangulate_polygons(loops);
  REQUIRE(t.status == TriangulationStatus::ok);
  CHECK(t.outer_loops == 2);
  CHECK(t.holes == 2);
  std::vector<Eigen::Vector2d> all;
  for (const auto& loop : loops) all.insert(all.end(), loop.begin(), loop.end());
  double area = 0.0;
  std::set<int> used;
  for (const auto& tri : t.triangles) {
    const double a = 0.5 * twice_signed_area({all[tri[0]], all[tri[1]], all[tri[2]]});
    CHECK(a > 0.0);
    area += a;
    used.insert(tri.begin(), tri.end());
  }
  CHECK(area == doctest::Approx(100.0 - 4.0 - 4.0 + 0.5).epsilon(1e-14));
  CHECK(used.size() == all.size());
  // n points, h holes, i islands: triangles = points + 2 (holes) - 2 (outer loops).
  CHECK(t.triangles.size() == all.size() + 2 * 2 - 2 * 2);
}

TEST_CASE("flatten_base: demo meshes, upright and posed stable, cut at many heights stay valid solids") {
  int cuts = 0;
  for (const std::string name : {"bottle", "top", "handle", "buoy"}) {
    const Mesh demo = make_demo_mesh(name);
    const Vector10d P = mass_properties(demo);
    const Mesh posed = apply_rigid_motion(demo, stable_pose(demo, P.segment<3>(kCx)).motion);
    for (const Mesh* mesh : {&demo, &posed}) {
      const double zmin = mesh->V.col(2).minCoeff(), zmax = mesh->V.col(2).maxCoeff();
      for (int k = 1; k < 16; ++k) {
        CAPTURE(name);
        CAPTURE(k);
        const FlattenResult r = flatten_base(*mesh, FlattenOptions{(zmax - zmin) * k / 16.0});
        REQUIRE(r.status == FlattenStatus::ok);
        const MeshValidation validation = validate_mesh(r.mesh);
        for (const Defect& defect : validation.defects) CHECK(defect.kind == DefectKind::several_components);
        CHECK(cap_figures(r).faces_down);
        CHECK(cap_figures(r).in_plane);
        // Relative to the whole volume: near the top the kept part is a small difference.
        if (r.snapped_vertices == 0)
          CHECK(std::fabs(volume_of(r.mesh) - (volume_of(*mesh) - volume_below(*mesh, r.plane_z))) <= 1e-12 * volume_of(*mesh));
        ++cuts;
      }
    }
  }
  CHECK(cuts == 4 * 2 * 15);
}
