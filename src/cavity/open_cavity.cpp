#include "cavity/open_cavity.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "cavity/printable_solid.h"
#include "geometry/bvh.h"
#include "geometry/closest_point.h"
#include "geometry/cylinder_prism.h"
#include "geometry/mesh_shells.h"
#include "geometry/plane_section.h"
#include "geometry/point_in_solid.h"
#include "geometry/ray_cast.h"
#include "geometry/subtract_convex.h"
#include "mass/volume_integrals.h"
#include "mesh/primitives.h"
#include "util/det_math.h"

namespace offsetopt {
namespace {

constexpr int kTries = 8;

struct Prism {
  Eigen::Vector3d inner, outer;
  double radius = 0.0;
};

// Cuts `prism` from `solid`, turning it a little after a degenerate try; composes source_face.
// `prism` and `record` are moved to where the prism was cut.
bool cut(Mesh& solid, std::vector<int>& source, Prism& prism, int sides, CutOpening& record, std::string& why) {
  const Eigen::Vector3d axis = (prism.outer - prism.inner).normalized();
  // Two directions across the axis: every try moves the prism sideways too (an automatic hole's
  // axis starts at a mesh vertex, and a contoured cavity has edges on lines through it).
  Eigen::Index least = 0;
  axis.cwiseAbs().minCoeff(&least);
  const Eigen::Vector3d across = (Eigen::Vector3d::Unit(least) - axis(least) * axis).normalized();
  const Eigen::Vector3d sideways = 0.61 * across + 0.79 * axis.cross(across);
  std::string last;
  for (int attempt = 0; attempt < kTries; ++attempt) {
    const Eigen::Vector3d shift = (1e-7 * prism.radius * attempt) * axis + (1e-5 * prism.radius * (attempt + 1)) * sideways;
    const Mesh cutter = cylinder_prism(prism.inner + shift, prism.outer + shift, prism.radius, sides, 0.0137 * attempt);
    const SubtractResult r = subtract_convex(solid, cutter);
    if (r.status == SubtractStatus::degenerate) {
      last = r.message;
      continue;
    }
    if (r.status != SubtractStatus::ok) {
      why = r.message;
      return false;
    }
    std::vector<int> composed(r.source_face.size(), -1);
    for (std::size_t f = 0; f < composed.size(); ++f)
      if (r.source_face[f] >= 0) composed[f] = source[static_cast<std::size_t>(r.source_face[f])];
    solid = r.mesh;
    source = std::move(composed);
    record.tries = attempt + 1;
    prism.inner += shift;
    prism.outer += shift;
    record.inner = prism.inner;
    record.outer = prism.outer;
    return true;
  }
  why = "every try of the cut was degenerate (the last: " + last + ")";
  return false;
}

// The void's extent along `direction` from `from` (a point on or in the cavity): the first exit.
double void_depth(const TriangleBvh& cavity_bvh, const Eigen::Vector3d& from, const Eigen::Vector3d& direction, double start) {
  RayCastOptions o;
  o.t_min = start;
  const RayCastHit hit = ray_cast_closest(cavity_bvh, from, direction, o);
  return hit.hit ? hit.t : 0.0;
}

Eigen::Vector3d unit(int axis) { return Eigen::Vector3d::Unit(axis); }

SectionPlane section_plane(int axis, double value) {
  return axis == 0 ? yz_plane(value) : axis == 1 ? xz_plane(value) : xy_plane(value);
}

// Distance from q to the polyline loops of a section (2-D).
double distance_to_loops(const PlaneSection& s, const Eigen::Vector2d& q) {
  double best = std::numeric_limits<double>::infinity();
  for (const SectionLoop& loop : s.loops)
    for (std::size_t i = 0; i < loop.points.size(); ++i) {
      const Eigen::Vector2d a = loop.points[i], b = loop.points[(i + 1) % loop.points.size()];
      const Eigen::Vector2d e = b - a;
      const double len2 = e.squaredNorm();
      const double t = len2 > 0.0 ? std::clamp((q - a).dot(e) / len2, 0.0, 1.0) : 0.0;
      best = std::min(best, (a + t * e - q).norm());
    }
  return best;
}

// Whether q lies inside the material of a section (even-odd over its loops).
bool inside_loops(const PlaneSection& s, const Eigen::Vector2d& q) {
  bool in = false;
  for (const SectionLoop& loop : s.loops)
    for (std::size_t i = 0; i < loop.points.size(); ++i) {
      const Eigen::Vector2d a = loop.points[i], b = loop.points[(i + 1) % loop.points.size()];
      if ((a.y() > q.y()) != (b.y() > q.y()) && q.x() < a.x() + (q.y() - a.y()) / (b.y() - a.y()) * (b.x() - a.x())) in = !in;
    }
  return in;
}

// Where a channel through a half-space region runs: the point (u, v) of the region's plane it
// crosses, that plane, and its room (the least distance from the axis to the outer surface's
// sections at 9 levels across the region: axis_room).
struct AxisChoice {
  Eigen::Vector2d point = Eigen::Vector2d::Zero();
  SectionPlane plane;
  double room = 0.0;
};

// The room of the axis through `c` across `levels` (the sections from the region's plane
// outwards): the least distance from it to every section, inside the material (the wall to keep)
// and, once it has left, outside (the channel passes the surface beyond by a wall too); none when
// it is outside the first section, or enters the material again after leaving it.
std::optional<double> axis_room(const std::vector<PlaneSection>& levels, const Eigen::Vector2d& c) {
  double room = std::numeric_limits<double>::infinity();
  bool left = false;
  for (std::size_t level = 0; level < levels.size(); ++level) {
    const PlaneSection& cut_here = levels[level];
    if (cut_here.loops.empty()) continue;
    const bool inside = inside_loops(cut_here, c);
    if (level == 0 && !inside) return std::nullopt;
    if (inside && left) return std::nullopt;
    left = left || !inside;
    room = std::min(room, distance_to_loops(cut_here, c));
  }
  return room;
}

// The axis through the area centroid of the largest section at the region's plane when its room
// keeps `wall` and a quarter more; else the point of a 16 × 16 grid over that section's box with the
// most room (first in grid order on a tie). On the 20 mm calibration cube, z>V over the top tenth
// crosses the engraved Z at its centroid.
std::optional<AxisChoice> choose_axis(const Mesh& outer, const FixRegion& region, double wall, std::string& why) {
  const int axis = region.axis;
  const double lo = outer.V.col(axis).minCoeff(), hi = outer.V.col(axis).maxCoeff();
  if (!(region.above ? region.value < hi : region.value > lo)) {
    why = "the region " + region.text + " holds no part of the surface";
    return std::nullopt;
  }
  const double far_end = region.above ? hi : lo;
  AxisChoice choice;
  choice.plane = section_plane(axis, region.value);
  std::vector<PlaneSection> levels;
  for (int level = 0; level < 9; ++level)
    levels.push_back(plane_section(outer, section_plane(axis, region.value + (far_end - region.value) * (level / 9.0))));
  const SectionLoop* largest = nullptr;
  for (const SectionLoop& loop : levels.front().loops)
    if (loop.signed_area > 0.0 && (!largest || loop.signed_area > largest->signed_area)) largest = &loop;
  if (!largest) {
    why = "the outer surface has no section at " + region.text;
    return std::nullopt;
  }
  // Area centroid of the largest loop (shoelace).
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  double a2 = 0.0;
  Eigen::Vector2d box_lo = largest->points.front(), box_hi = box_lo;
  for (std::size_t i = 0; i < largest->points.size(); ++i) {
    const Eigen::Vector2d p = largest->points[i], q = largest->points[(i + 1) % largest->points.size()];
    const double cr = p.x() * q.y() - q.x() * p.y();
    a2 += cr;
    c += cr * (p + q);
    box_lo = box_lo.cwiseMin(p);
    box_hi = box_hi.cwiseMax(p);
  }
  c /= 3.0 * a2;
  if (const std::optional<double> room = axis_room(levels, c); room && *room >= 1.25 * wall) {
    choice.point = c;
    choice.room = *room;
    return choice;
  }
  std::optional<double> best;
  constexpr int kSide = 16;
  for (int j = 0; j < kSide; ++j)
    for (int i = 0; i < kSide; ++i) {
      const Eigen::Vector2d t((i + 0.5) / kSide, (j + 0.5) / kSide);
      const Eigen::Vector2d q = box_lo + t.cwiseProduct(box_hi - box_lo);
      const std::optional<double> room = axis_room(levels, q);
      if (room && (!best || *room > *best)) {
        best = room;
        choice.point = q;
      }
    }
  if (!best) {
    why = "no line along the region's axis stays inside the outer surface across " + region.text;
    return std::nullopt;
  }
  choice.room = *best;
  return choice;
}

// The channel for a half-space region: see the header.
bool channel_prism(const Mesh& outer, const TriangleBvh& cavity_bvh, const OpenCavityOptions& options, Prism& prism,
                   std::string& why) {
  const FixRegion& region = options.opening;
  const int axis = region.axis;
  const double s = region.above ? 1.0 : -1.0;
  const double far_end = region.above ? outer.V.col(axis).maxCoeff() : outer.V.col(axis).minCoeff();
  const std::optional<AxisChoice> chosen = choose_axis(outer, region, options.wall, why);
  if (!chosen) return false;
  const Eigen::Vector2d c = chosen->point;
  const SectionPlane& base = chosen->plane;
  const double room = chosen->room;
  double radius = room - options.wall;
  if (options.max_channel_radius > 0.0) radius = std::min(radius, options.max_channel_radius);
  if (!(radius >= 0.25 * options.wall)) {
    why = "the outer surface inside " + region.text + " leaves no room for a channel with the wall (" +
          std::to_string(room) + " from its axis)";
    return false;
  }
  const Eigen::Vector3d centre = region.value * unit(axis) + c.x() * base.u + c.y() * base.v;
  const Eigen::Vector3d direction = -s * unit(axis);  // from outside the far end into the object
  const Eigen::Vector3d start = centre + (far_end - region.value + s * 2.0 * options.wall) * unit(axis);
  // The channel must end inside the void: every prism corner's ray (and the axis) enters the cavity,
  // and the end sits before the void's far side on each. Where the cavity is narrower than the
  // room, the radius shrinks (×0.8, at most 12 times).
  double depth = 0.0;
  bool fits = false;
  for (int shrink = 0; shrink < 12 && !fits; ++shrink, radius *= 0.8) {
    if (!(radius >= 0.25 * options.wall)) break;
    double deepest_entry = -std::numeric_limits<double>::infinity();
    double shallowest_exit = std::numeric_limits<double>::infinity();
    bool all_hit = true;
    for (int k = -1; k < options.sides && all_hit; ++k) {
      Eigen::Vector3d from = start;
      if (k >= 0) {
        double sine = 0.0, cosine = 0.0;
        det_sincos(6.283185307179586 * k / options.sides, sine, cosine);
        from += radius * (cosine * base.u + sine * base.v);
      }
      const RayCastHit entry = ray_cast_closest(cavity_bvh, from, direction, RayCastOptions{});
      if (!entry.hit) {
        all_hit = false;
        break;
      }
      const double exit = void_depth(cavity_bvh, from, direction, entry.t);
      deepest_entry = std::max(deepest_entry, entry.t);
      shallowest_exit = std::min(shallowest_exit, exit > 0.0 ? exit : entry.t);
    }
    if (!all_hit || !(shallowest_exit > deepest_entry)) continue;
    depth = std::min(deepest_entry + 0.5 * radius, 0.5 * (deepest_entry + shallowest_exit));
    fits = true;
    radius /= 0.8;  // undo the loop's step
  }
  if (!fits) {
    why = "the channel inside " + region.text + " does not reach into the cavity";
    return false;
  }
  prism.outer = start;
  prism.inner = start + depth * direction;
  prism.radius = radius;
  return true;
}

// The opening for a sphere region: see the header.
bool sphere_opening_prism(const TriangleBvh& outer_bvh, const TriangleBvh& cavity_bvh, const OpenCavityOptions& options,
                          Prism& prism, std::string& why) {
  const FixRegion& region = options.opening;
  const Eigen::Vector3d centre(region.center[0], region.center[1], region.center[2]);
  const ClosestPoint mouth = closest_point(outer_bvh, centre);
  if (!mouth.found || !(mouth.distance < region.radius)) {
    why = "the region " + region.text + " holds no part of the outer surface";
    return false;
  }
  const ClosestPoint end = closest_point(cavity_bvh, mouth.point);
  const Eigen::Vector3d into_void = end.found ? (end.point - mouth.point).normalized() : Eigen::Vector3d::Zero();
  if (!end.found || !into_void.allFinite() || into_void.isZero()) {
    why = "the cavity has no point apart from the outer surface near " + region.text;
    return false;
  }
  RayCastOptions far_side;
  far_side.ignored_faces.push_back(end.face);  // the ray starts on it
  far_side.t_min = 1e-9 * outer_bvh.diagonal();
  const RayCastHit far = ray_cast_closest(cavity_bvh, end.point, into_void, far_side);
  const double depth = far.hit ? far.t : 0.0;
  const Eigen::Vector3d u = into_void.unitOrthogonal(), v = into_void.cross(u);
  double radius = 0.5 * std::sqrt(region.radius * region.radius - mouth.distance * mouth.distance);
  if (options.max_channel_radius > 0.0) radius = std::min(radius, options.max_channel_radius);
  for (int shrink = 0; shrink < 12; ++shrink, radius *= 0.8) {
    if (!(radius >= 0.25 * options.wall)) break;
    const Eigen::Vector3d inner = end.point + std::min(0.5 * radius, 0.45 * depth) * into_void;
    bool inside = point_in_solid(cavity_bvh, inner);
    for (int k = 0; k < options.sides && inside; ++k) {
      double sine = 0.0, cosine = 0.0;
      det_sincos(6.283185307179586 * k / options.sides, sine, cosine);
      inside = point_in_solid(cavity_bvh, inner + radius * (cosine * u + sine * v));
    }
    if (!inside) continue;
    prism.inner = inner;
    prism.outer = mouth.point - (radius + 2.0 * options.wall) * into_void;
    prism.radius = radius;
    return true;
  }
  why = "the void near " + region.text + " leaves no room for an opening of a quarter wall's radius";
  return false;
}

}  // namespace

std::optional<ChannelAxis> channel_axis(const Mesh& outer, const FixRegion& region, double wall, std::string& why) {
  if (region.kind != FixRegion::Kind::half_space) {
    why = "only a half-space region has a channel";
    return std::nullopt;
  }
  const std::optional<AxisChoice> chosen = choose_axis(outer, region, wall, why);
  if (!chosen) return std::nullopt;
  const SectionPlane& base = chosen->plane;
  ChannelAxis line;
  line.direction = (region.above ? 1.0 : -1.0) * unit(region.axis);
  line.point = region.value * unit(region.axis) + chosen->point.x() * base.u + chosen->point.y() * base.v;
  return line;
}

std::string OpenCavityOptions::check() const {
  if (!(wall > 0.0)) return "the wall must be positive";
  if (!(hole_radius > 0.0)) return "the drain hole radius must be positive";
  if (sides < 3 || sides > 256) return "the prism needs 3 to 256 sides";
  for (const DrainHoleRequest& h : holes)
    if (!h.point.allFinite() || (h.radius >= 0.0 && !(h.radius > 0.0))) return "a drain hole needs a finite point and a positive radius";
  return "";
}

OpenedCavity open_cavity(const Mesh& outer, const Mesh& cavity, const OpenCavityOptions& options) {
  OpenedCavity out;
  if (const std::string problem = options.check(); !problem.empty()) {
    out.message = problem;
    return out;
  }
  if (cavity.F.rows() == 0) {
    // Nothing to drain: automatic holes have no shell to go to; a hole or channel asked for
    // explicitly has no void to reach.
    if (!options.holes.empty() || options.opening.kind != FixRegion::Kind::none) {
      out.message = "there is no cavity to open";
      return out;
    }
    out.solid = outer;
    out.source_face.resize(static_cast<std::size_t>(outer.F.rows()));
    for (std::size_t f = 0; f < out.source_face.size(); ++f) out.source_face[f] = static_cast<int>(f);
    out.ok = true;
    return out;
  }
  const Eigen::Vector3d origin = mean_vertex(outer);
  const TriangleBvh outer_bvh(outer.V, outer.F), cavity_bvh(cavity.V, cavity.F);
  const MeshShells shells = mesh_shells(cavity, origin);
  out.cavity_shells = shells.count;
  out.solid = hollow_solid(outer, cavity);
  out.source_face.resize(static_cast<std::size_t>(out.solid.F.rows()));
  for (std::size_t f = 0; f < out.source_face.size(); ++f) out.source_face[f] = static_cast<int>(f);
  out.pieces_before = mesh_shells(out.solid, origin).count;

  std::vector<std::pair<Prism, CutOpening>> cuts;
  auto hole_through_nearest = [&](const Eigen::Vector3d& p, double radius, double inside, const std::string& kind, int shell) {
    const ClosestPoint q = closest_point(outer_bvh, p);
    Prism prism;
    const Eigen::Vector3d out_dir = (q.point - p).normalized();
    prism.inner = p - inside * out_dir;
    prism.outer = q.point + (radius + 2.0 * options.wall) * out_dir;
    prism.radius = radius;
    CutOpening record;
    record.kind = kind;
    record.inner = prism.inner;
    record.outer = prism.outer;
    record.radius = radius;
    record.shell = shell;
    cuts.emplace_back(prism, record);
  };
  for (const DrainHoleRequest& h : options.holes) {
    if (!point_in_solid(cavity_bvh, h.point)) {
      out.message = "the drain hole point (" + std::to_string(h.point.x()) + ", " + std::to_string(h.point.y()) + ", " +
                    std::to_string(h.point.z()) + ") is not in the cavity";
      return out;
    }
    hole_through_nearest(h.point, h.radius > 0.0 ? h.radius : options.hole_radius, 0.0, "drain hole", -1);
  }
  if (options.auto_holes) {
    std::vector<int> lowest(static_cast<std::size_t>(shells.count), -1);
    for (Eigen::Index f = 0; f < cavity.F.rows(); ++f) {
      int& best = lowest[static_cast<std::size_t>(shells.shell_of_face[static_cast<std::size_t>(f)])];
      for (int c = 0; c < 3; ++c) {
        const int v = cavity.F(f, c);
        if (best < 0 || cavity.V(v, 2) < cavity.V(best, 2) || (cavity.V(v, 2) == cavity.V(best, 2) && v < best)) best = v;
      }
    }
    for (int s = 0; s < shells.count; ++s) {
      const int vertex = lowest[static_cast<std::size_t>(s)];
      const Eigen::Vector3d p = cavity.V.row(vertex).transpose();
      // Into the void along the cavity's inward vertex normal (its faces point out of the void),
      // not away from the outer surface: where the offset surface, not the wall, bounds the cavity
      // the two differ, and a hole whose end only grazes the void opens nothing.
      RayCastOptions far_side;
      Eigen::Vector3d normal = Eigen::Vector3d::Zero();
      for (Eigen::Index f = 0; f < cavity.F.rows(); ++f)
        if ((cavity.F.row(f).array() == vertex).any()) {
          far_side.ignored_faces.push_back(static_cast<int>(f));  // the ray starts on them
          const Eigen::Vector3d a = cavity.V.row(cavity.F(f, 0)).transpose();
          normal += (cavity.V.row(cavity.F(f, 1)).transpose() - a).cross(cavity.V.row(cavity.F(f, 2)).transpose() - a);
        }
      const Eigen::Vector3d into_void = -normal.normalized();
      const RayCastHit hit = ray_cast_closest(cavity_bvh, p, into_void, far_side);
      const double depth = hit.hit ? hit.t : 0.0;
      const Eigen::Vector3d start = p + std::min(0.5 * options.hole_radius, 0.45 * depth) * into_void;
      hole_through_nearest(start, options.hole_radius, 0.0, "auto drain hole", s);
    }
  }
  if (options.opening.kind != FixRegion::Kind::none) {
    Prism prism;
    std::string why;
    const bool sphere = options.opening.kind == FixRegion::Kind::sphere;
    if (sphere ? !sphere_opening_prism(outer_bvh, cavity_bvh, options, prism, why)
               : !channel_prism(outer, cavity_bvh, options, prism, why)) {
      out.message = why;
      return out;
    }
    CutOpening record;
    record.kind = sphere ? "opening" : "channel";
    record.inner = prism.inner;
    record.outer = prism.outer;
    record.radius = prism.radius;
    cuts.emplace_back(prism, record);
  }
  if (cuts.empty()) {
    out.message = "no opening was asked for";
    return out;
  }
  for (auto& [prism, record] : cuts) {
    std::string why;
    if (!cut(out.solid, out.source_face, prism, options.sides, record, why)) {
      out.message = record.kind + " could not be cut: " + why;
      return out;
    }
    if (record.kind == "channel" || record.kind == "opening") {
      // Where the channel's side meets the outer surface: new vertices on it (within rounding).
      double spill = std::numeric_limits<double>::infinity();
      const double tol = 1e-9 * outer_bvh.diagonal();
      const Eigen::Vector3d along = (prism.outer - prism.inner).normalized();
      for (Eigen::Index v = 0; v < out.solid.V.rows(); ++v) {
        const Eigen::Vector3d p = out.solid.V.row(v).transpose();
        const Eigen::Vector3d radial = (p - prism.inner) - (p - prism.inner).dot(along) * along;
        const double inscribed = prism.radius * det_cos(3.141592653589793 / options.sides);
        if (radial.norm() < inscribed * (1.0 - 1e-9) - tol || radial.norm() > prism.radius * (1.0 + 1e-9) + tol) continue;  // not on the prism's side
        const ClosestPoint c = closest_point(outer_bvh, p, 1e3 * tol);
        if (!c.found || c.distance > 1e3 * tol) continue;
        spill = std::min(spill, p.z());
      }
      if (std::isfinite(spill)) out.spill_height = spill;
    }
    out.openings.push_back(record);
  }
  // A prism grazing a thin feature can cut a chip of material loose: a closed piece of positive
  // volume below 1e-3 of the largest. It would fall out of the print, so it is dropped (its
  // integrals leave the solid's); a closed piece of negative volume is a cavity left closed.
  const MeshShells after = mesh_shells(out.solid, origin);
  double largest = 0.0;
  for (double v : after.volume) largest = std::max(largest, v);
  std::vector<char> drop(static_cast<std::size_t>(after.count), 0);
  int closed_cavities = 0;
  for (int piece = 0; piece < after.count; ++piece) {
    const double v = after.volume[static_cast<std::size_t>(piece)];
    if (v < 0.0) ++closed_cavities;
    else if (v < 1e-3 * largest) drop[static_cast<std::size_t>(piece)] = 1;
  }
  for (char d : drop) out.chips_dropped += d;
  if (out.chips_dropped > 0) {
    Mesh kept;
    std::vector<int> source, index(static_cast<std::size_t>(out.solid.V.rows()), -1);
    std::vector<Eigen::Index> faces;
    for (Eigen::Index f = 0; f < out.solid.F.rows(); ++f)
      if (!drop[static_cast<std::size_t>(after.shell_of_face[static_cast<std::size_t>(f)])]) faces.push_back(f);
    int count = 0;
    for (Eigen::Index f : faces)
      for (int c = 0; c < 3; ++c)
        if (index[static_cast<std::size_t>(out.solid.F(f, c))] < 0) index[static_cast<std::size_t>(out.solid.F(f, c))] = count++;
    kept.V.resize(count, 3);
    for (Eigen::Index v = 0; v < out.solid.V.rows(); ++v)
      if (index[static_cast<std::size_t>(v)] >= 0) kept.V.row(index[static_cast<std::size_t>(v)]) = out.solid.V.row(v);
    kept.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
    for (std::size_t i = 0; i < faces.size(); ++i) {
      for (int c = 0; c < 3; ++c) kept.F(static_cast<Eigen::Index>(i), c) = index[static_cast<std::size_t>(out.solid.F(faces[i], c))];
      source.push_back(out.source_face[static_cast<std::size_t>(faces[i])]);
    }
    out.solid = std::move(kept);
    out.source_face = std::move(source);
  }
  out.pieces_after = after.count - out.chips_dropped;
  if (closed_cavities > 0) {
    out.message = std::to_string(closed_cavities) + " cavity shell(s) stay closed after the openings";
    return out;
  }
  out.ok = true;
  return out;
}

bool cut_by_plane(const Mesh& mesh, int axis, double level, bool keep_above, Mesh& out) {
  const Eigen::Vector3d lo = mesh.V.colwise().minCoeff().transpose(), hi = mesh.V.colwise().maxCoeff().transpose();
  const double size = (hi - lo).norm();
  for (int attempt = 0; attempt < kTries; ++attempt) {
    const double at = level - (keep_above ? -1.0 : 1.0) * 1e-9 * size * attempt;
    Eigen::Vector3d box_lo = lo - Eigen::Vector3d::Constant(0.1 * size), box_hi = hi + Eigen::Vector3d::Constant(0.1 * size);
    if (keep_above) box_hi(axis) = at;  // remove what lies below
    else box_lo(axis) = at;
    if (!(box_lo(axis) < box_hi(axis))) {
      out = keep_above ? Mesh() : mesh;
      return true;
    }
    const SubtractResult r = subtract_convex(mesh, make_box(box_lo, box_hi));
    if (r.status == SubtractStatus::degenerate) continue;
    if (r.status != SubtractStatus::ok) return false;
    out = r.mesh;
    return true;
  }
  return false;
}

}  // namespace offsetopt
