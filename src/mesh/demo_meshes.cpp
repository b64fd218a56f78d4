#include "mesh/demo_meshes.h"

#include <cmath>
#include <stdexcept>
#include <utility>

#include "mesh/primitives.h"
#include "util/det_math.h"

namespace offsetopt {

namespace {

// A revolution profile (radius, z) from the bottom pole to the top pole, built from segments
// and arcs; each piece appends its points after the current one.
class Profile {
 public:
  // `detail` scales every piece's step count (1: the demo meshes as committed).
  explicit Profile(double z_pole, double detail = 1.0) : detail_(detail) { points_.emplace_back(0.0, z_pole); }

  double r() const { return points_.back().first; }
  double z() const { return points_.back().second; }

  void line_to(double r1, double z1, int steps) {
    steps = scaled(steps);
    const double r0 = r(), z0 = z();
    for (int k = 1; k <= steps; ++k) {
      const double s = static_cast<double>(k) / steps;
      points_.emplace_back(r0 + (r1 - r0) * s, z0 + (z1 - z0) * s);
    }
  }

  // Arc of the circle (center_r, center_z, radius) at angles t0 -> t1 (t = 0 points to +r,
  // t = pi/2 to +z); the current point should be the arc's start.
  void arc(double center_r, double center_z, double radius, double t0, double t1, int steps) {
    steps = scaled(steps);
    for (int k = 1; k <= steps; ++k) {
      double s, c;
      det_sincos(t0 + (t1 - t0) * k / steps, s, c);
      points_.emplace_back(center_r + radius * c, center_z + radius * s);
    }
  }

  // S-shaped blend to (r1, z1): the radius follows (1 - cos(pi s)) / 2 while z moves linearly,
  // so the tangent is vertical at both ends and the profile stays smooth.
  void blend_to(double r1, double z1, int steps) {
    steps = scaled(steps);
    const double r0 = r(), z0 = z();
    for (int k = 1; k <= steps; ++k) {
      const double s = static_cast<double>(k) / steps;
      const double weight = 0.5 * (1.0 - det_cos(kPi * s));
      points_.emplace_back(r0 + (r1 - r0) * weight, z0 + (z1 - z0) * s);
    }
  }

  // Straight to the axis at height z1: steps - 1 rings, then the top pole.
  void close_to_axis(double z1, int steps) {
    steps = scaled(steps);
    const double r0 = r(), z0 = z();
    for (int k = 1; k < steps; ++k) {
      const double s = static_cast<double>(k) / steps;
      points_.emplace_back(r0 * (1.0 - s), z0 + (z1 - z0) * s);
    }
    points_.emplace_back(0.0, z1);
  }

  // Arc that ends on the axis at its top (angle pi/2), the last point snapped to the pole.
  void arc_to_top_pole(double center_z, double radius, double t0, int steps) {
    arc(0.0, center_z, radius, t0, 0.5 * kPi, steps);  // arc() scales the steps
    points_.back() = {0.0, center_z + radius};
  }

  const std::vector<std::pair<double, double>>& points() const { return points_; }

 private:
  int scaled(int steps) const {
    if (detail_ == 1.0) return steps;
    const int n = static_cast<int>(steps * detail_);
    return n > 2 ? n : 2;
  }

  double detail_;
  std::vector<std::pair<double, double>> points_;
};

constexpr int kSegments = 64;  // vertices per ring of every revolution demo (at detail 1)

int segments(double detail) {
  const int n = static_cast<int>(kSegments * detail);
  return n > 8 ? n : 8;
}

double bounding_box_diagonal(const Mesh& mesh) {
  return (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).norm();
}

// Translates the mesh vertically so its lowest vertex is exactly at z = 0.
void rest_on_ground(Mesh& mesh) {
  const double z_min = mesh.V.col(2).minCoeff();
  mesh.V.col(2).array() -= z_min;
}

// x += k z: a shear, linear and invertible, so the mesh stays free of self-intersections and a
// cavity inside stays inside; horizontal slices only translate, the base on z = 0 stays put.
void lean(Mesh& mesh, double k) { mesh.V.col(0) += k * mesh.V.col(2); }

// Scales each horizontal slice radially about the z axis by 1 + amount * w(angle) * h(z), with
// w = ((1 + cos angle) / 2)^4 (largest towards +x, symmetric in y) and h a quartic bump of
// half-width `half_height` around `center_z`. Per slice a positive scaling of a star-shaped
// curve about its centre, so a bijection of space: nothing can intersect.
void radial_lump(Mesh& mesh, double amount, double center_z, double half_height) {
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    const double x = mesh.V(i, 0), y = mesh.V(i, 1), z = mesh.V(i, 2);
    const double rho = std::sqrt(x * x + y * y);
    const double t = (z - center_z) / half_height;
    if (rho == 0.0 || std::fabs(t) >= 1.0) continue;
    const double h = (1.0 - t * t) * (1.0 - t * t);
    const double toward = 0.5 * (1.0 + x / rho);
    const double w = toward * toward * toward * toward;
    const double scale = 1.0 + amount * w * h;
    mesh.V(i, 0) = x * scale;
    mesh.V(i, 1) = y * scale;
  }
}

// ---- bottle ---------------------------------------------------------------------------------

struct BottleShape {
  double bottom = 0.0;        // z of the flat base
  double foot_radius = 31.0;  // radius of the flat contact disc
  double heel = 4.0;          // fillet between base and body
  double body_top = 150.0;
  double neck_radius = 13.0;
  double neck_bottom = 195.0;
  double height = 245.0;
  double lip = 2.5;           // fillet at the top rim
};
constexpr double kBottleLean = 0.45;

Mesh bottle_surface(const BottleShape& s, double detail = 1.0) {
  Profile p(s.bottom, detail);
  p.line_to(s.foot_radius, s.bottom, 5);
  p.arc(s.foot_radius, s.bottom + s.heel, s.heel, -0.5 * kPi, 0.0, 3);  // first ring 0.54 up: off the ground
  p.line_to(s.foot_radius + s.heel, s.body_top, 16);
  p.blend_to(s.neck_radius, s.neck_bottom, 12);
  p.line_to(s.neck_radius, s.height - s.lip, 8);
  p.arc(s.neck_radius - s.lip, s.height - s.lip, s.lip, 0.0, 0.5 * kPi, 4);
  p.close_to_axis(s.height, 5);
  Mesh mesh = make_revolution(p.points(), segments(detail));
  lean(mesh, kBottleLean);
  return mesh;
}

Mesh bottle(double detail) { return bottle_surface(BottleShape{}, detail); }

Mesh bottle_cavity() {
  const BottleShape outer;
  const double wall = 0.01 * bounding_box_diagonal(bottle_surface(outer));
  BottleShape inner = outer;
  inner.bottom = 0.35 * outer.body_top;  // a thick solid bottom keeps the mass low and upright
  // Radii shrink by 1.1 walls because the shear thins the leaning side by 1/sqrt(1 + k^2); the
  // shoulder also drops by 0.6 walls so its slope does not thin it (normal distance >= 1 wall).
  inner.foot_radius = outer.foot_radius - 1.1 * wall;
  inner.neck_radius = outer.neck_radius - 1.1 * wall;
  inner.body_top = outer.body_top - 0.6 * wall;
  inner.neck_bottom = outer.neck_bottom - 0.6 * wall;
  inner.height = outer.height - 1.1 * wall;
  return bottle_surface(inner);
}

// ---- spinning top ---------------------------------------------------------------------------

Mesh top(double detail) {
  Profile p(0.0, detail);  // the tip: a single pole vertex, the unique lowest point
  p.line_to(28.0, 16.0, 14);
  p.arc(28.0, 19.0, 3.0, -0.5 * kPi, 0.5 * kPi, 8);
  p.line_to(6.0, 26.0, 10);
  p.blend_to(4.0, 30.0, 3);
  p.line_to(4.0, 44.0, 7);
  p.arc(2.0, 44.0, 2.0, 0.0, 0.5 * kPi, 3);
  p.close_to_axis(46.0, 3);
  Mesh mesh = make_revolution(p.points(), segments(detail));
  radial_lump(mesh, 0.08, 19.0, 9.0);
  return mesh;
}

Mesh top_cavity() {
  // An ellipsoid in the rim's +x half: between the cone below (z = 16 r / 28) and the upper
  // face above (from (28, 22) to (6, 26)).
  Mesh lens = make_icosphere(1.0, 3);
  const Eigen::Vector3d center(14.5, 0.0, 19.0), radii(11.5, 12.0, 3.8);
  for (Eigen::Index i = 0; i < lens.V.rows(); ++i)
    for (int c = 0; c < 3; ++c) lens.V(i, c) = center(c) + radii(c) * lens.V(i, c);
  return lens;
}

// ---- roly-poly ------------------------------------------------------------------------------

constexpr double kRolyRadius = 30.0;

Mesh rolypoly_surface(double wall, double void_bottom, double detail = 1.0) {
  const double r = kRolyRadius;
  // Horizontal offsets thin a sloped wall by cos(slope): the neck (up to 54 degrees from
  // vertical) is offset by 1.7 walls, the torso blends from 1 to 1.7 walls.
  const double neck_wall = 1.7 * wall;
  const double head_radius = 16.0 - wall, head_center = 80.0, neck = 10.0 - neck_wall;
  const double head_t0 = -det_acos(neck / head_radius);
  double s0, c0;
  det_sincos(head_t0, s0, c0);
  Profile p(void_bottom, detail);
  if (wall == 0.0) {
    p.arc(0.0, r, r, -0.5 * kPi, 0.0, 16);  // the hemisphere
  } else {
    // The cavity: a flat floor at void_bottom out to the shrunk sphere, then up its wall.
    const double rr = r - wall, dz = r - void_bottom;
    const double floor_radius = std::sqrt(rr * rr - dz * dz);
    p.line_to(floor_radius, void_bottom, 6);
    p.arc(0.0, r, rr, -det_asin(dz / rr), 0.0, 6);
  }
  p.blend_to(20.0 - neck_wall, 56.0, 12);
  p.blend_to(neck, head_center + head_radius * s0, 5);
  p.arc_to_top_pole(head_center, head_radius, head_t0, 14);
  return make_revolution(p.points(), segments(detail));
}

Mesh rolypoly(double detail) {
  Mesh mesh = rolypoly_surface(0.0, 0.0, detail);
  radial_lump(mesh, 0.3, 80.0, 10.0);  // a nose on the +x side of the head
  return mesh;
}

Mesh rolypoly_cavity() {
  const double wall = 0.01 * bounding_box_diagonal(rolypoly(1.0));
  return rolypoly_surface(wall, 0.95 * kRolyRadius);
}

// ---- buoy -----------------------------------------------------------------------------------

constexpr double kBuoyRadius = 35.0;

// Round hull (a hemisphere of kBuoyRadius under a short cylinder), an ogive deck, a mast and a
// lamp. With wall > 0: the cavity, from a flat floor at void_bottom (in the cylinder) up the
// shrunk hull and deck.
Mesh buoy_surface(double wall, double void_bottom, double detail = 1.0) {
  const double R = kBuoyRadius, hull_top = 55.0, mast = 4.0, deck_top = 70.0;
  Profile p(void_bottom, detail);
  if (wall == 0.0) {
    p.arc(0.0, R, R, -0.5 * kPi, 0.0, 16);
  } else {
    if (!(void_bottom >= R && void_bottom < hull_top)) throw std::logic_error("buoy cavity floor outside the hull's cylinder");
    p.line_to(R - wall, void_bottom, 8);
  }
  // The cavity's deck drops by 1 to 2 walls so that the nearly flat middle of the ogive keeps a
  // full wall along its normal.
  p.line_to(R - wall, hull_top - wall, 8);
  p.blend_to(mast - wall, deck_top - 2.0 * wall, 12);
  if (wall != 0.0) {
    p.close_to_axis(deck_top - 2.0 * wall, 3);
    return make_revolution(p.points(), kSegments);
  }
  p.line_to(mast, 88.0, 10);
  const double lamp = 6.0;
  p.arc_to_top_pole(88.0 + std::sqrt(lamp * lamp - mast * mast), lamp, -det_acos(mast / lamp), 10);
  return make_revolution(p.points(), segments(detail));
}

Mesh buoy(double detail) { return buoy_surface(0.0, 0.0, detail); }

Mesh buoy_cavity() { return buoy_surface(0.01 * bounding_box_diagonal(buoy(1.0)), 44.0); }

// ---- handle ---------------------------------------------------------------------------------

Mesh handle() {
  // A unit-tube torus re-swept: in the meridian half-plane at angle u the tube is a circle of
  // radius r(u) = 2 + 10 ((1 + cos u) / 2)^2 centred at height r(u), so it lies flat on z = 0.
  // The circles sit in disjoint half-planes and never reach the axis, so nothing intersects.
  const double R = 40.0;
  Mesh mesh = make_torus(R, 1.0, 96, 32);
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    const double x = mesh.V(i, 0), y = mesh.V(i, 1), z = mesh.V(i, 2);
    const double rho = std::sqrt(x * x + y * y);
    const double cos_u = x / rho, sin_u = y / rho;
    const double cos_v = rho - R, sin_v = z;
    const double toward = 0.5 * (1.0 + cos_u);
    const double r = 2.0 + 10.0 * toward * toward;
    const double rho_new = R + r * cos_v;
    mesh.V(i, 0) = rho_new * cos_u;
    mesh.V(i, 1) = rho_new * sin_u;
    mesh.V(i, 2) = r + r * sin_v;
  }
  return mesh;
}

}  // namespace

std::vector<std::string> demo_mesh_names() {
  return {"bottle", "top", "rolypoly", "buoy", "handle", "sphere", "capsule", "torus", "top-coarse"};
}

Mesh make_demo_mesh(const std::string& name, double detail) {
  const bool revolution = name == "bottle" || name == "top" || name == "rolypoly" || name == "buoy";
  if (!(detail >= 0.25 && detail <= 32.0)) throw std::invalid_argument("detail must be in [0.25, 32]");
  if (detail != 1.0 && !revolution)
    throw std::invalid_argument("detail applies to bottle, top, rolypoly and buoy, not to '" + name + "'");
  Mesh mesh;
  if (name == "bottle") mesh = bottle(detail);
  else if (name == "top") mesh = top(detail);
  else if (name == "top-coarse") mesh = top(0.5);
  else if (name == "rolypoly") mesh = rolypoly(detail);
  else if (name == "buoy") mesh = buoy(detail);
  else if (name == "handle") mesh = handle();
  else if (name == "sphere") mesh = make_icosphere(30.0, 4);
  else if (name == "capsule") mesh = make_capsule(15.0, 25.0, kSegments, 16, 16);
  else if (name == "torus") mesh = make_torus(30.0, 10.0, 96, 32);
  else throw std::invalid_argument("unknown demo mesh '" + name + "'");
  rest_on_ground(mesh);
  return mesh;
}

Mesh make_demo_cavity(const std::string& name) {
  if (name == "bottle") return bottle_cavity();
  if (name == "top") return top_cavity();
  if (name == "rolypoly") return rolypoly_cavity();
  if (name == "buoy") return buoy_cavity();
  throw std::invalid_argument("no demo cavity for '" + name + "'");
}

}  // namespace offsetopt
