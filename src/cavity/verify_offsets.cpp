#include "cavity/verify_offsets.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <future>
#include <limits>

#include "cavity/new_self_intersections.h"
#include "geometry/bvh.h"
#include "geometry/closest_point.h"
#include "geometry/intersecting_faces.h"
#include "mass/mass_properties.h"
#include "mass/stability.h"
#include "mass/volume_integrals.h"
#include "util/parallel.h"
#include "util/det_math.h"
#include "util/format_double.h"

namespace offsetopt {

namespace {

struct Check {
  Verification& out;
  void require(bool ok, const std::string& failure) {
    if (!ok) out.failures.push_back(failure);
  }
};

StabilityFigures stability_figures(const Stability& s) {
  StabilityFigures figures;
  figures.com_margin = s.com_margin;
  figures.tipping_angle_deg = s.tipping_angle_deg;
  figures.stands = s.stands;
  return figures;
}

// Faces with no fixed corner: contacts at the opening (where the surfaces coincide) are by design.
Mesh without_fixed_faces(const Mesh& mesh, const std::vector<char>& fixed) {
  Mesh out;
  out.V = mesh.V;
  std::vector<int> rows;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    bool touches = false;
    for (int c = 0; c < 3; ++c) touches = touches || fixed[static_cast<std::size_t>(mesh.F(f, c))];
    if (!touches) rows.push_back(static_cast<int>(f));
  }
  out.F.resize(static_cast<Eigen::Index>(rows.size()), 3);
  for (std::size_t r = 0; r < rows.size(); ++r) out.F.row(static_cast<Eigen::Index>(r)) = mesh.F.row(rows[r]);
  return out;
}

// Directed edges without their opposite, and edges used more than once in one direction: 0 for a
// closed, consistently oriented, edge-manifold mesh.
long long unmatched_edges(const Mesh& mesh) {
  // One key per directed edge: the undirected edge (lower, higher index) and which way it runs.
  // Sorting integers is several times faster than pairs on a contoured cavity (7e5 edges).
  std::vector<std::uint64_t> keys;
  keys.reserve(static_cast<std::size_t>(3 * mesh.F.rows()));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const std::uint64_t a = static_cast<std::uint32_t>(mesh.F(f, c)), b = static_cast<std::uint32_t>(mesh.F(f, (c + 1) % 3));
      keys.push_back((std::min(a, b) << 32) | (std::max(a, b) << 1) | (a > b ? 1u : 0u));
    }
  std::sort(keys.begin(), keys.end());
  long long bad = 0;
  for (std::size_t e = 0; e < keys.size();) {
    std::size_t end = e;
    long long runs[2] = {0, 0};
    while (end < keys.size() && (keys[end] >> 1) == (keys[e] >> 1)) ++runs[keys[end++] & 1u];
    const bool loop = (keys[e] >> 32) == ((keys[e] >> 1) & 0x7fffffffu);
    if (loop) {
      bad += runs[0] - 1;  // (a, a) is its own opposite: only repeats count
    } else {
      for (int way = 0; way < 2; ++way) {
        if (runs[way] > 1) bad += runs[way] - 1;  // used more than once in this direction
        if (runs[1 - way] == 0) bad += runs[way];  // no edge the other way
      }
    }
    e = end;
  }
  return bad;
}

}  // namespace

SurfaceDefects find_surface_defects(const Mesh& outer, const Mesh& inner, const std::vector<char>& fixed,
                                    const std::vector<char>& left_solid, double thin_below, int threads,
                                    const IntersectingFaces* inner_self, const TriangleBvh* inner_tree,
                                    const TriangleBvh* outer_tree, const WallBounds& wall_bounds) {
  // The two trees, then the two intersection searches, on two threads when there are: the same
  // result either way.
  WorkerPool pool(std::min(std::max(threads, 1), 2));
  const bool any_fixed = std::find(fixed.begin(), fixed.end(), char{1}) != fixed.end();
  auto is_fixed = [&](std::size_t u) { return !fixed.empty() && fixed[u]; };
  auto is_left_solid = [&](std::size_t u) { return !left_solid.empty() && left_solid[u]; };
  Mesh inner_kept, outer_kept;
  if (any_fixed) {
    inner_kept = without_fixed_faces(inner, fixed);
    outer_kept = without_fixed_faces(outer, fixed);
  }
  const Mesh& inner_free = any_fixed ? inner_kept : inner;
  const Mesh& outer_free = any_fixed ? outer_kept : outer;
  TriangleBvh inner_built, outer_built;
  const bool have_tree = inner_tree && !any_fixed, have_outer_tree = outer_tree && !any_fixed;
  pool.run_parts(2, [&](int part) {
    if (part == 0 && !have_tree) inner_built = TriangleBvh(inner_free.V, inner_free.F);
    if (part == 1 && !have_outer_tree) outer_built = TriangleBvh(outer_free.V, outer_free.F);
  });
  const TriangleBvh& inner_bvh = have_tree ? *inner_tree : inner_built;
  const TriangleBvh& outer_bvh = have_outer_tree ? *outer_tree : outer_built;
  const std::size_t cap = 100000;
  const bool known = inner_self && !any_fixed && !inner_self->truncated;
  IntersectingFaces self_part[2], crossing;
  if (known) {
    crossing = intersecting_faces_in_parts(inner_bvh, outer_bvh, cap, threads);
  } else {
    pool.run_parts(2, [&](int part) {
      self_part[part] = self_intersections_part(inner_bvh, part, cap);
      if (part == 1) crossing = intersecting_faces(inner_bvh, outer_bvh, cap);
    });
  }
  const IntersectingFaces self = known ? *inner_self : merge_intersections(self_part[0], self_part[1], cap);
  SurfaceDefects d;
  d.self_intersection_pairs = self.pairs.size();
  d.crossing_pairs = crossing.pairs.size();
  d.truncated = self.truncated || crossing.truncated;
  std::vector<char> flagged(static_cast<std::size_t>(inner.V.rows()), 0);
  for (const auto& p : self.pairs)
    for (int f : {p.first, p.second})
      for (int c = 0; c < 3; ++c) flagged[static_cast<std::size_t>(inner_free.F(f, c))] = 1;
  for (const auto& p : crossing.pairs)
    for (int c = 0; c < 3; ++c) flagged[static_cast<std::size_t>(inner_free.F(p.first, c))] = 1;
  for (std::size_t i = 0; i < flagged.size(); ++i)
    if (flagged[i]) d.intersecting_vertices.push_back(static_cast<int>(i));

  // Without fixed vertices the whole outer surface is the tree already built.
  TriangleBvh outer_whole;
  if (any_fixed) outer_whole = TriangleBvh(outer.V, outer.F);
  const TriangleBvh& outer_full = any_fixed ? outer_whole : outer_bvh;
  // Ranges of the vertices (kWallParts from 1,024 vertices on), in vertex order within each, on two
  // threads when there are. In each, the thinnest wall found so far prunes every later search, and
  // so does `seed`, the thinnest of a few vertices spread over all of them: without it a range
  // starting in a thick region searches wide balls until it reaches a thin one (halves without a
  // seed took 0.22 s on a 100k-vertex bottle where the one pass took 0.055). The last vertex
  // searched is an anchor: the distance is 1-Lipschitz, so a vertex whose bound from the anchor's
  // (exact, or the search radius when nothing was nearer) reaches the radius needs no search.
  // Searching twice the radius makes anchors that cover the next vertices (neighbours on a
  // contoured cavity lie a fraction of the wall apart) and still prunes the BVH.
  //
  // A vertex whose known lower bound (WallBounds, less its slack) reaches the radius is skipped the
  // same way: it is known to be farther.
  //
  // Why the split changes nothing: the seed is some vertex's distance, so at least the thinnest
  // wall m. A vertex skipped or not found is farther than the pruning radius, which is at least
  // thin_below and at least min(seed, the range's thinnest so far) >= m: it is neither thin nor
  // the first vertex at m. Every other vertex's distance is closest_point's whatever the bound,
  // and is recorded when below thin_below or the range's thinnest so far (not the seed: the seed's
  // own vertex may be the thinnest). The merge takes the first range's vertex on a tie and joins
  // the thin lists in order: the one pass's result for any split and any seed.
  struct WallScan {
    double thinnest = std::numeric_limits<double>::infinity();
    int vertex = -1;
    std::vector<int> thin;
  };
  const double rounding = 1e-12 * outer_full.diagonal();
  const bool bounds_fit = wall_bounds.known && wall_bounds.known->size() == static_cast<std::size_t>(inner.V.rows());
  const std::vector<double>* known_lower = bounds_fit ? wall_bounds.known : nullptr;
  std::vector<double>* record = wall_bounds.record;
  if (record) record->assign(static_cast<std::size_t>(inner.V.rows()), 0.0);
  auto measured_vertex = [&](Eigen::Index i) {
    const std::size_t u = static_cast<std::size_t>(i);
    return !is_fixed(u) && !is_left_solid(u);
  };
  auto scan = [&](Eigen::Index begin, Eigen::Index end, double seed) {
    WallScan w;
    Eigen::Vector3d anchor = Eigen::Vector3d::Zero();
    double anchor_distance = -std::numeric_limits<double>::infinity();
    for (Eigen::Index i = begin; i < end; ++i) {
      if (!measured_vertex(i)) continue;
      // Only distances below the thinnest so far or below thin_below matter.
      const double radius = std::max(thin_below, std::min(seed, w.thinnest));
      const Eigen::Vector3d p = inner.V.row(i).transpose();
      const std::size_t u = static_cast<std::size_t>(i);
      if (known_lower && (*known_lower)[u] - wall_bounds.slack >= radius + rounding) continue;
      const double from_anchor = anchor_distance - (p - anchor).norm();
      if (from_anchor >= radius + rounding) {
        if (record) (*record)[u] = from_anchor;
        continue;
      }
      const ClosestPoint c = closest_point(outer_full, p, 2.0 * radius);
      anchor = p;
      anchor_distance = c.found ? c.distance : 2.0 * radius;
      if (record) (*record)[u] = anchor_distance;
      if (!c.found || !(c.distance < std::max(thin_below, w.thinnest))) continue;
      if (c.distance < w.thinnest) {
        w.thinnest = c.distance;
        w.vertex = static_cast<int>(i);
      }
      if (c.distance < thin_below) w.thin.push_back(static_cast<int>(i));
    }
    return w;
  };
  // Below this many vertices a thread costs more than the share it saves.
  constexpr Eigen::Index kWallSplitVertices = 1024;
  constexpr int kWallParts = 16;
  constexpr int kWallSeedVertices = 16;
  const Eigen::Index count = inner.V.rows();
  const bool split = count >= kWallSplitVertices;
  double seed = std::numeric_limits<double>::infinity();
  if (split)
    for (int k = 0; k < kWallSeedVertices; ++k) {
      const Eigen::Index i = count * k / kWallSeedVertices;
      if (!measured_vertex(i)) continue;
      const ClosestPoint c = closest_point(outer_full, inner.V.row(i).transpose(), seed);
      if (c.found) seed = c.distance;
    }
  // With two threads, kWallParts ranges taken by whichever thread is free: the wall binds on part
  // of a cavity only, and two fixed halves left one thread idle at the end (the buoy's quadric void).
  const int parts = split ? kWallParts : 1;
  std::vector<WallScan> scanned(static_cast<std::size_t>(parts));
  pool.run_parts_balanced(parts, [&](int part) {
    scanned[static_cast<std::size_t>(part)] = scan(split_point(count, parts, part), split_point(count, parts, part + 1), seed);
  });
  const WallScan* won = &scanned[0];
  for (const WallScan& w : scanned)
    if (w.thinnest < won->thinnest) won = &w;  // the first range's vertex on a tie
  d.thinnest_wall = won->thinnest;
  d.thinnest_vertex = won->vertex;
  for (const WallScan& w : scanned) d.thin_wall_vertices.insert(d.thin_wall_vertices.end(), w.thin.begin(), w.thin.end());
  return d;
}

Verification verify_offsets(const VerifyInput& in) {
  Verification out;
  Check check{out};
  const Mesh& outer = *in.outer;
  const Mesh& inner = *in.inner;
  const double diag = in.diagonal;
  const double position_tol = 1e-4 * diag;
  // The cavity's closedness beside the integrals (both read only `inner`), on a thread of its
  // own when there are two.
  std::future<long long> open_edges_task;
  if (!in.goal_only) open_edges_task = start_task(in.threads > 1, [&inner] { return unmatched_edges(inner); });

  // The integrals of the printed material, measured from a point near the object.
  const Eigen::Vector3d origin = mean_vertex(outer);
  VolumeIntegrals outer_int = volume_integrals(outer, origin), inner_int = volume_integrals(inner, origin);
  const VolumeIntegrals shell = subtract(outer_int, inner_int);
  const Vector10d P = mass_properties(shell);
  const Eigen::Vector3d com(P(kCx), P(kCy), P(kCz));
  GoalFigures& m = out.goal;
  m.goal = in.goal.kind;
  m.mass = P(kMass);
  m.void_volume = inner_int.values(kIntVolume);
  m.outer_volume = outer_int.values(kIntVolume);
  m.center_of_mass = com;

  StabilityOptions stability_options;
  stability_options.ground_tol = in.ground_tol;
  const GoalSpec& g = in.goal;
  switch (g.kind) {
    case GoalKind::stand:
    case GoalKind::stand_filled: {
      const Stability empty = compute_stability(outer, com, stability_options);
      m.empty = stability_figures(empty);
      check.require(empty.com_margin >= g.margin,
                    "the centre of mass is " + format_double(empty.com_margin) + " inside the support polygon, less than the margin " +
                        format_double(g.margin));
      if (g.kind == GoalKind::stand_filled) {
        VolumeIntegrals filled = shell;
        filled.values += g.fill_density * (in.liquid ? volume_integrals(*in.liquid, origin).values : inner_int.values);
        const Vector10d Pf = mass_properties(filled);
        const Stability full = compute_stability(outer, Eigen::Vector3d(Pf(kCx), Pf(kCy), Pf(kCz)), stability_options);
        m.filled = stability_figures(full);
        m.filled_center_of_mass = Eigen::Vector3d(Pf(kCx), Pf(kCy), Pf(kCz));
        check.require(full.com_margin >= g.margin, "filled, the centre of mass is " + format_double(full.com_margin) +
                                                       " inside the support polygon, less than the margin " + format_double(g.margin));
      }
      break;
    }
    case GoalKind::roly_poly: {
      const double off_axis = std::hypot(P(kCx) - g.axis_point.x(), P(kCy) - g.axis_point.y());
      const double below = g.axis_point.z() - P(kCz);
      m.axis_point = g.axis_point;
      m.com_off_axis = off_axis;
      m.com_below_center = below;
      check.require(off_axis <= position_tol, "the centre of mass is " + format_double(off_axis) + " off the sphere's vertical axis");
      check.require(below > g.epsilon * (1.0 - 1e-9), "the centre of mass is not below the sphere centre by the margin (" +
                                                          format_double(below) + " < " + format_double(g.epsilon) + ")");
      break;
    }
    case GoalKind::spin: {
      const double off_axis = std::hypot(P(kCx) - g.axis_point.x(), P(kCy) - g.axis_point.y());
      const PrincipalInertia principal = principal_inertia(P);
      // The principal axis closest to z and the angle between them.
      int axis = 0;
      for (int a = 1; a < 3; ++a)
        if (std::fabs(principal.axes(2, a)) > std::fabs(principal.axes(2, axis))) axis = a;
      const double tilt = det_acos(std::min(1.0, std::fabs(principal.axes(2, axis)))) * 180.0 / kPi;
      const bool largest = axis == 2;
      m.axis_point = g.axis_point;
      m.com_off_axis = off_axis;
      m.izx_over_izz = P(kIzx) / P(kIzz);
      m.iyz_over_izz = P(kIyz) / P(kIzz);
      m.principal_moments = principal.moments;
      m.spin_axis_tilt_deg = tilt;
      m.spin_axis_is_largest_moment = largest;
      check.require(off_axis <= position_tol, "the centre of mass is " + format_double(off_axis) + " off the spin axis");
      check.require(std::fabs(P(kIzx)) <= 1e-4 * P(kIzz) && std::fabs(P(kIyz)) <= 1e-4 * P(kIzz),
                    "the inertia products Izx, Iyz are not below 1e-4 Izz");
      check.require(tilt <= 0.5, "the principal axis is tilted " + format_double(tilt) + " degrees from z");
      check.require(largest, "z is not the axis of the largest principal moment: the spin is not stable");
      break;
    }
    case GoalKind::volume: {
      const double relative = (inner_int.values(kIntVolume) - g.target_volume) / g.target_volume;
      m.target_volume = g.target_volume;
      m.volume_relative_error = relative;
      check.require(std::fabs(relative) <= in.volume_tolerance, "the void holds " + format_double(inner_int.values(kIntVolume)) +
                                                     " instead of " + format_double(g.target_volume));
      break;
    }
    case GoalKind::floating: {
      const double v_out = outer_int.values(kIntVolume);
      const Eigen::Vector3d buoyancy = origin + Eigen::Vector3d(outer_int.values(kIntX), outer_int.values(kIntY),
                                                                outer_int.values(kIntZ)) / v_out;
      const double imbalance = g.fluid_density * v_out - P(kMass);
      const double off_axis = std::hypot(P(kCx) - buoyancy.x(), P(kCy) - buoyancy.y());
      m.center_of_buoyancy = buoyancy;
      m.buoyancy_minus_weight = imbalance;
      m.com_off_buoyancy_axis = off_axis;
      m.com_below_buoyancy = buoyancy.z() - P(kCz);
      check.require(std::fabs(imbalance) <= 1e-3 * P(kMass), "buoyancy and weight differ by " + format_double(imbalance));
      check.require(off_axis <= position_tol, "the centre of mass is " + format_double(off_axis) + " off the buoyancy axis");
      check.require(P(kCz) < buoyancy.z(), "the centre of mass is above the centre of buoyancy: it would flip");
      break;
    }
  }
  out.goal_met = out.failures.empty();
  if (in.goal_only) return out;

  // Validity of the solid.
  const std::size_t goal_failures = out.failures.size();
  // The wall is met up to rounding: 1e-9 of it.
  const double thin_below = in.wall * (1.0 - 1e-9);
  // The rounding searched the cavity as written already (cavity/round_for_output.h).
  const bool searched = in.rounding && in.rounding->inner_searched && in.inner == &in.rounding->inner;
  const SurfaceDefects defects =
      find_surface_defects(outer, inner, in.fixed, {}, thin_below, in.threads, searched ? &in.rounding->inner_pairs : nullptr,
                           searched ? in.rounding->inner_tree.get() : nullptr,
                           searched && in.outer == &in.rounding->outer ? in.rounding->outer_tree.get() : nullptr,
                           in.wall_bounds);
  ValidityFigures& v = out.validity.emplace();
  v.inner_self_intersections = static_cast<long long>(defects.self_intersection_pairs);
  v.inner_outer_crossings = static_cast<long long>(defects.crossing_pairs);
  const std::string more = defects.truncated ? "+" : "";
  check.require(defects.self_intersection_pairs == 0,
                "the inner surface intersects itself (" + std::to_string(defects.self_intersection_pairs) + more + " face pairs)");
  check.require(defects.crossing_pairs == 0,
                "the inner surface crosses the outer surface (" + std::to_string(defects.crossing_pairs) + more + " face pairs)");
  if (in.outer_own_pairs) {
    const NewSelfIntersections outer_self = new_self_intersections(outer, *in.outer_own_pairs, 100000, in.threads);
    v.outer_new_self_intersections = outer_self.pairs;
    v.outer_own_self_intersections = outer_self.own_pairs_kept;
    check.require(outer_self.pairs == 0, "the thickened outer surface intersects itself (" + std::to_string(outer_self.pairs) +
                                             (outer_self.truncated ? "+" : "") + " face pairs the input does not have, first: faces " +
                                             std::to_string(outer_self.first_face) + " and " +
                                             std::to_string(outer_self.second_face) + ")");
  }
  const bool measured = std::isfinite(defects.thinnest_wall);
  const long long open_edges = open_edges_task.get();
  v.cavity_unmatched_edges = open_edges;
  check.require(open_edges == 0, "the cavity is not closed: " + std::to_string(open_edges) +
                                     " of its edges are not shared by exactly two faces in opposite directions");
  v.requested_wall = in.wall;
  if (measured) v.min_wall_measured = defects.thinnest_wall;
  v.min_wall_vertex = defects.thinnest_vertex;
  v.largest_bound_violation = in.bound_violation;
  if (measured)
    check.require(defects.thin_wall_vertices.empty(), "the wall is " + format_double(defects.thinnest_wall) +
                                                          " thin at inner vertex " + std::to_string(defects.thinnest_vertex) +
                                                          ", less than the requested " + format_double(in.wall));
  check.require(in.bound_violation <= 1e-6 * diag, "the offsets leave their bounds by " + format_double(in.bound_violation));
  v.precision = in.precision;
  if (in.rounding) {
    v.vertices_moved_for_rounding = in.rounding->vertices_moved;
    v.rounding_new_defects = in.rounding->outer_new_pairs + in.rounding->inner_new_pairs;
    check.require(v.rounding_new_defects == 0,
                  "rounded to float32 as the STL file stores it, the surfaces have " + std::to_string(v.rounding_new_defects) +
                      " self-intersecting face pairs or collinear faces that the unrounded surfaces lack (outer " +
                      std::to_string(in.rounding->outer_new_pairs) + ", cavity " + std::to_string(in.rounding->inner_new_pairs) +
                      "); a .ply, .obj or .3mf output keeps every digit");
  }
  out.valid = out.failures.size() == goal_failures;
  return out;
}

VerifiedCavity verify_written_cavity(VerifyInput input, const Mesh& outer, const Mesh& cavity, int faces_below_wall,
                                    StoredPrecision precision) {
  VerifiedCavity out;
  out.rounded = round_for_output(outer, cavity, {}, precision, input.threads);
  input.outer = &out.rounded.outer;
  input.inner = &out.rounded.inner;
  input.rounding = &out.rounded;
  input.goal_only = false;
  out.verification = verify_offsets(input);
  if (faces_below_wall > 0) {
    out.verification.valid = false;
    out.verification.failures.push_back(std::to_string(faces_below_wall) +
                                        " cavity faces come closer to the outer surface than the wall between their vertices");
  }
  return out;
}

}  // namespace offsetopt
