#include "cavity/contour_cavity.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <iterator>
#include <limits>
#include <memory>
#include <tuple>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "geometry/closest_point.h"
#include "geometry/face_shortlist.h"
#include "geometry/grid_winding.h"
#include "geometry/marching_tetrahedra.h"
#include "geometry/mesh_shells.h"
#include "geometry/triangle_distance.h"
#include "util/parallel.h"
#include "util/sort_in_parts.h"

namespace offsetopt {

namespace {

constexpr double kMinFraction = 1e-3;  // marching tetrahedra: how close to a node a vertex may sit

// A hair above the wall that covers rounding the written file's coordinates to float32.
double rounding_hair(double wall, const Aabb& outer_box) {
  const Eigen::Vector3d far = outer_box.lo.cwiseAbs().cwiseMax(outer_box.hi.cwiseAbs());
  return 4e-7 * (far.norm() + (outer_box.hi - outer_box.lo).norm()) + 1e-9 * wall;
}
constexpr int kBlock = 4;              // nodes per block side in the distance pass
constexpr int kParts = 2;              // every parallel loop is cut into this many fixed parts
// but the distance pass, the vertex placement and the wall check, whose cost varies by region (the
// wall binds on part of the cavity only): 32 parts taken by whichever thread is free. On the buoy's
// quadric void two halves left one thread idle a third of the time.
constexpr int kBalancedParts = 32;
constexpr int kRaiseRounds = 8;        // rounds that lift the vertices of faces below the wall
constexpr int kDemotions = 3;          // contours again with the void nodes of faces that stayed below
constexpr int kRootSteps = 48;         // cap on the distance queries that put one vertex on the wall
// Void nodes keep the target plus this many cells: room to lift a vertex towards its node where a
// face dips below the wall (on real meshes 1% of the faces dip by 2–6% of the wall, the deepest by
// 10–15%), and more than the kMinFraction of an edge (at most √2 h) that a vertex always keeps
// from its node. Nodes this close to the wall are material, so the contour passes near them: the
// price is at most this much of h, on part of the surface (a face parallel to a grid plane can
// sit that high all over). Faces a lift cannot mend are contoured again instead, which costs a
// whole pass: 0.08 h made that rare but cost the demo bottle 0.04 mm of its centre of mass.
constexpr double kNodeRoom = 0.02;

// closest_point(bvh, p, max_distance), its walk bounded from the start by the distance to `hint`
// (a face likely near p, or -1): the same answer, since the bound is above the nearest face's
// squared distance (the hint's, computed as closest_point computes it) whenever it lowers it.
ClosestPoint closest_point_hinted(const TriangleBvh& bvh, const Eigen::Vector3d& p, double max_distance, int hint) {
  if (hint >= 0) {
    const Eigen::Vector3d q = closest_point_on_triangle(p, bvh.corner(hint, 0), bvh.corner(hint, 1), bvh.corner(hint, 2));
    const double bound = (q - p).norm() * (1.0 + 1e-9) + 1e-12 * (1.0 + p.cwiseAbs().maxCoeff());
    if (bound < max_distance) return closest_point(bvh, p, bound);
  }
  return closest_point(bvh, p, max_distance);
}

// The inner term of φ: which nodes lie inside the void it bounds, and a signed distance to its
// boundary (positive inside), capped at ±cap.
class InnerField {
 public:
  virtual ~InnerField() = default;
  virtual Aabb box() const = 0;  // where the void can be
  virtual std::vector<std::int8_t> inside(const NodeGrid& grid, const std::vector<std::int8_t>& outer_winding,
                                          int threads) const = 0;
  // `near`: faces gathered by gather_near for a region around p (any region: the list only
  // changes the cost), or nullptr.
  virtual double signed_distance(const Eigen::Vector3d& p, bool inside, double cap, const FaceShortlist* near = nullptr) const = 0;
  // Fills `near` for signed_distance at points within `radius` − cap of `centre`, when the field
  // has faces to gather (else leaves it empty).
  virtual void gather_near(const Eigen::Vector3d& /*centre*/, double /*radius*/, FaceShortlist& /*near*/) const {}
  // Where the void's boundary first crosses the grid edge from p (a void node) towards q, as a
  // fraction of the edge; 1 when it does not cross. s_p, s_q: signed_distance at p and q. By
  // default the zero of the linear interpolation.
  virtual double crossing(const Eigen::Vector3d& /*p*/, const Eigen::Vector3d& /*q*/, double s_p, double s_q) const {
    return s_q < 0.0 ? s_p / (s_p - s_q) : 1.0;
  }
};

// The inner offset surface: inside where its winding number is >= 1 (folds and overlaps resolve
// themselves), the distance to its nearest face.
class MeshField final : public InnerField {
 public:
  MeshField(const Mesh& inner, const GridWinding* known) : inner_(inner), bvh_(inner.V, inner.F), known_(known) {}
  Aabb box() const override { return bounding_box(inner_.V); }
  std::vector<std::int8_t> inside(const NodeGrid& grid, const std::vector<std::int8_t>&, int threads) const override {
    std::vector<std::int8_t> winding = known_ && same_grid(known_->grid, grid) &&
                                               known_->winding.size() == static_cast<std::size_t>(grid.node_count())
                                           ? known_->winding
                                           : grid_winding(inner_, grid, threads);
    for (std::int8_t& w : winding) w = w >= 1;
    return winding;
  }
  double signed_distance(const Eigen::Vector3d& p, bool inside, double cap, const FaceShortlist* near) const override {
    const ClosestPoint to_inner = near && !near->empty() ? near->nearest(bvh_, p, cap) : closest_point(bvh_, p, cap);
    const double d_in = to_inner.found ? to_inner.distance : cap;
    return inside ? d_in : -d_in;
  }
  void gather_near(const Eigen::Vector3d& centre, double radius, FaceShortlist& near) const override {
    near.gather(bvh_, centre, radius);
  }

 private:
  const Mesh& inner_;
  TriangleBvh bvh_;
  const GridWinding* known_;
};

// The quadric void { q < 0 }: its signed distance to first order, −q/|∇q| (Taubin's estimate,
// exact for a plane, within O(distance²) of the true distance near the surface). The
// coefficients are re-expanded about the centre of the outer box once, so that a model far from
// the origin loses no digits to cancellation at every node.
class QuadricField final : public InnerField {
 public:
  QuadricField(const Vector10d& c, const Aabb& outer_box) : box_(outer_box), centre_(0.5 * (outer_box.lo + outer_box.hi)) {
    const Eigen::Vector3d& o = centre_;
    // q(o + u) = q(o) + ∇q(o)·u + the same quadratic part.
    a_ = c;
    a_(0) = value_at(c, o);
    a_(1) = c(1) + 2.0 * c(4) * o.x() + c(7) * o.y() + c(9) * o.z();
    a_(2) = c(2) + 2.0 * c(5) * o.y() + c(7) * o.x() + c(8) * o.z();
    a_(3) = c(3) + 2.0 * c(6) * o.z() + c(8) * o.y() + c(9) * o.x();
  }
  Aabb box() const override { return box_; }
  std::vector<std::int8_t> inside(const NodeGrid& grid, const std::vector<std::int8_t>& outer_winding,
                                  int threads) const override {
    std::vector<std::int8_t> in(static_cast<std::size_t>(grid.node_count()), 0);
    WorkerPool pool(std::max(1, std::min(threads, kParts)));
    pool.run_parts(kParts, [&](int part) {
      for (std::int64_t k = split_point(grid.nz, kParts, part); k < split_point(grid.nz, kParts, part + 1); ++k)
        for (std::int64_t j = 0; j < grid.ny; ++j)
          for (std::int64_t i = 0; i < grid.nx; ++i) {
            const std::int64_t node = grid.index(i, j, k);
            if (outer_winding[static_cast<std::size_t>(node)] < 1) continue;
            in[static_cast<std::size_t>(node)] = local_value(Eigen::Vector3d(grid.x(i), grid.y(j), grid.z(k)) - centre_) < 0.0;
          }
    });
    return in;
  }
  double signed_distance(const Eigen::Vector3d& p, bool inside, double cap, const FaceShortlist*) const override {
    const Eigen::Vector3d u = p - centre_;
    const double q = local_value(u);
    const double gradient = local_gradient(u).norm();
    // Where |∇q| vanishes (a centre, an apex) the estimate is unbounded: the cap stands in for it.
    double s = std::fabs(q) >= cap * gradient ? cap : std::fabs(q) / gradient;
    if (!inside) s = -s;
    return s;
  }
  // The quadric along the edge is a quadratic in the fraction, so its first root is exact.
  double crossing(const Eigen::Vector3d& p, const Eigen::Vector3d& q, double, double) const override {
    const Eigen::Vector3d u = p - centre_, e = q - p;
    const double c = local_value(u);
    const double b = local_gradient(u).dot(e);
    const double a = a_(4) * e.x() * e.x() + a_(5) * e.y() * e.y() + a_(6) * e.z() * e.z() + a_(7) * e.x() * e.y() +
                     a_(8) * e.y() * e.z() + a_(9) * e.z() * e.x();
    if (!(c < 0.0)) return 0.0;  // p is not inside after all (rounding): no void on this edge
    double first = 1.0;
    auto take = [&](double t) {
      if (t > 0.0 && t < first) first = t;
    };
    if (a == 0.0) {
      if (b > 0.0) take(-c / b);
      return first;
    }
    const double discriminant = b * b - 4.0 * a * c;
    if (discriminant < 0.0) return first;
    // The two roots without cancellation: one from the quadratic formula, the other from the
    // product of the roots (c / a).
    const double s = b >= 0.0 ? -b - std::sqrt(discriminant) : -b + std::sqrt(discriminant);
    take(s / (2.0 * a));
    if (s != 0.0) take(2.0 * c / s);
    return first;
  }

 private:
  static double value_at(const Vector10d& c, const Eigen::Vector3d& p) {
    const double x = p.x(), y = p.y(), z = p.z();
    return c(0) + c(1) * x + c(2) * y + c(3) * z + c(4) * x * x + c(5) * y * y + c(6) * z * z + c(7) * x * y +
           c(8) * y * z + c(9) * z * x;
  }
  double local_value(const Eigen::Vector3d& u) const { return value_at(a_, u); }
  Eigen::Vector3d local_gradient(const Eigen::Vector3d& u) const {
    const double x = u.x(), y = u.y(), z = u.z();
    return Eigen::Vector3d(a_(1) + 2.0 * a_(4) * x + a_(7) * y + a_(9) * z, a_(2) + 2.0 * a_(5) * y + a_(7) * x + a_(8) * z,
                           a_(3) + 2.0 * a_(6) * z + a_(8) * y + a_(9) * x);
  }

  Aabb box_;
  Eigen::Vector3d centre_;
  Vector10d a_;
};


// The exact distance to the outer surface (the verification's own measure, closest_point's) at
// points of one grid edge, from faces gathered around the edge when its first point is asked; the
// list serves the next edges (the contour's vertices come cell by cell) while it covers them.
class EdgeDistances {
 public:
  // p + t e, t in [0, 1], with distances d_p and d_q at the ends: 1-Lipschitz, the distance at
  // p + t e plus |t − 1/2| |e| is at most max(d_p, d_q) + |e|/2, which sizes the gathering (a
  // capped d_p only costs the exact fallback); spare: how much wider to gather, for the edges
  // that follow.
  EdgeDistances(const TriangleBvh& bvh, FaceShortlist& near, const Eigen::Vector3d& p, const Eigen::Vector3d& e,
                double d_p, double d_q, double spare)
      : bvh_(bvh), near_(near), mid_(p + 0.5 * e), reach_(0.5 * e.norm() + std::max(d_p, d_q)), spare_(spare) {}
  double at(const Eigen::Vector3d& x) {
    if (!near_.covers(mid_, reach_)) near_.gather(bvh_, mid_, reach_ + spare_);
    const ClosestPoint c = near_.nearest(bvh_, x, std::numeric_limits<double>::infinity(), hint_);
    hint_ = c.face;
    return c.distance;
  }

 private:
  const TriangleBvh& bvh_;
  FaceShortlist& near_;
  Eigen::Vector3d mid_;
  double reach_, spare_;
  int hint_ = -1;
};

// A vertex placed on its grid edge: the fraction, a lower bound of its distance to the outer
// surface (exact where it was measured), and whether the wall put it there.
struct Placement {
  double fraction = kMinFraction;
  double lower = 0.0;
  bool on_wall = false;
};

// A point of [a, b] where the exact distance along p + t e is within [target, target + tolerance]
// (regula falsi aimed at the middle of that band, Illinois steps), given f = distance − aim at
// both ends (fa >= 0 > fb). Returns the fraction and its distance, or the last good end.
std::pair<double, double> wall_point(EdgeDistances& outer, const Eigen::Vector3d& p, const Eigen::Vector3d& e,
                                     double a, double fa, double b, double fb, double aim, double tolerance) {
  double good = a, good_distance = fa + aim;
  int side = 0;
  for (int step = 0; step < kRootSteps && good_distance - aim > 0.5 * tolerance; ++step) {
    double t = (a * fb - b * fa) / (fb - fa);
    if (!(t > a && t < b)) t = 0.5 * (a + b);
    const double distance = outer.at(p + t * e);
    const double f = distance - aim;
    if (f >= -0.5 * tolerance) {
      good = t;
      good_distance = distance;
      if (f <= 0.5 * tolerance) break;
      a = t;
      fa = f;
      if (side == 1) fb *= 0.5;
      side = 1;
    } else {
      b = t;
      fb = f;
      if (side == -1) fa *= 0.5;
      side = -1;
    }
    if (b - a <= 1e-15) break;
  }
  return {good, good_distance};
}

// The first point of the edge p → q (p a void node) where either the inner boundary is crossed
// (fraction t_in) or the distance to the outer surface falls to `target`; d_p and d_q are the
// nodes' distances (exact, or lower bounds when beyond the cap). The wall's point is aimed at
// target + tolerance/2 and accepted within tolerance/2 of it, so every vertex keeps the target,
// at most `tolerance` above it. Vertices never come nearer the node than kMinFraction: `lower`
// then says what they keep (below the target only for a lifted target the node cannot give).
Placement place_on_edge(const TriangleBvh& outer_bvh, FaceShortlist& near, const Eigen::Vector3d& p, const Eigen::Vector3d& q, double d_p,
                        double d_q, double t_in, double target, double tolerance, double rounding) {
  const Eigen::Vector3d e = q - p;
  const double length = e.norm();
  Placement out;
  out.fraction = t_in;
  if (d_p - t_in * length >= target + rounding) {  // 1-Lipschitz: the whole way keeps the target
    out.lower = d_p - t_in * length;
    return out;
  }
  const double aim = target + 0.5 * tolerance;
  out.on_wall = true;
  if (d_p <= aim) {  // a lifted target beyond what the node has: as near the node as allowed
    out.fraction = kMinFraction;
    out.lower = d_p - kMinFraction * length;
    return out;
  }
  // An edge the inner boundary does not cross: bracket with the nodes' own distances (no query;
  // exact for a plane on the first step). Otherwise measure where the inner boundary would put it.
  double t_wall = t_in, lower = 0.0;
  const bool whole_edge = t_in >= 1.0 - kMinFraction && d_q < aim;
  // An edge's width of spare: measured on the bottle, 0.25, 0.5, 1, 2 and 4 edges placed the
  // vertices in 420, 400, 393, 412 and 503 M instructions (gathering against scanning).
  EdgeDistances outer(outer_bvh, near, p, e, d_p, d_q, length);
  if (whole_edge) {
    std::tie(t_wall, lower) = wall_point(outer, p, e, 0.0, d_p - aim, 1.0, d_q - aim, aim, tolerance);
  }
  if (!whole_edge || t_wall > t_in) {
    const double d_end = outer.at(p + t_in * e);
    if (d_end >= target) {
      out.on_wall = false;
      out.lower = d_end;
      return out;
    }
    std::tie(t_wall, lower) = wall_point(outer, p, e, 0.0, d_p - aim, t_in, d_end - aim, aim, tolerance);
  }
  if (t_wall >= kMinFraction && lower >= target) {
    out.fraction = t_wall;
    out.lower = lower;
  } else {
    out.fraction = kMinFraction;
    out.lower = d_p - kMinFraction * length;
  }
  return out;
}

// Per face of `faces`, how far it comes below the wall (0 when it keeps it). A face is accepted
// by its vertices' lower bounds when every point of it lies within (longest edge)/√3 of a vertex
// (Jung's bound for a triangle); the rest are measured exactly against the outer faces within
// the wall, gathered once per run of consecutive faces (neighbours: the contour is made cell by
// cell). An outer face whose plane has the whole triangle on one side, a wall away, is passed
// over without the exact triangle distance (on a locally convex outer surface: all of them), and
// so is one that a plane separating it from the triangle's centroid keeps a wall away.
std::vector<double> face_deficits(const TriangleBvh& outer_bvh, const Mesh& mesh, const std::vector<double>& lower,
                                  const std::vector<int>& faces, double wall, WorkerPool& pool) {
  constexpr std::size_t kRun = 16;
  std::vector<double> deficit(faces.size(), 0.0);
  auto gap = [](const Aabb& x, const Aabb& y) {
    double squared = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double g = std::max({0.0, x.lo(k) - y.hi(k), y.lo(k) - x.hi(k)});
      squared += g * g;
    }
    return squared;
  };
  const double wall_squared = wall * wall;
  auto corner = [&](int f, int c) -> Eigen::Vector3d { return mesh.V.row(mesh.F(f, c)).transpose(); };
  auto face_box = [&](int f) {
    Aabb box;
    for (int c = 0; c < 3; ++c) box.extend(corner(f, c));
    return box;
  };
  // An outer face as the runs read it: its corners, its normal (not unit) and wall × |normal|,
  // computed once per run rather than once per face of the run.
  struct OuterFace {
    Eigen::Vector3d g0, g1, g2, n;
    double scale = 0.0;
    const Aabb* box = nullptr;
  };
  // The faces of one run against the outer faces gathered for the whole run.
  auto measure_run = [&](const std::vector<long>& run, const Aabb& run_box, std::vector<OuterFace>& nearby) {
    nearby.clear();
    outer_bvh.traverse([&](const Aabb& node) { return gap(node, run_box) < wall_squared; },
                       [&](int g) {
                         if (gap(outer_bvh.face_box(g), run_box) < wall_squared) {
                           OuterFace o;
                           o.g0 = outer_bvh.corner(g, 0);
                           o.g1 = outer_bvh.corner(g, 1);
                           o.g2 = outer_bvh.corner(g, 2);
                           o.n = (o.g1 - o.g0).cross(o.g2 - o.g0);
                           o.scale = wall * o.n.norm();
                           o.box = &outer_bvh.face_box(g);
                           nearby.push_back(o);
                         }
                         return true;
                       });
    for (const long i : run) {
      const int f = faces[static_cast<std::size_t>(i)];
      const Eigen::Vector3d a = corner(f, 0), b = corner(f, 1), c = corner(f, 2);
      const Aabb box = face_box(f);
      const Eigen::Vector3d centroid = (a + b + c) / 3.0;
      double best = wall;
      for (const OuterFace& o : nearby) {
        if (gap(*o.box, box) >= best * best) continue;
        const Eigen::Vector3d &g0 = o.g0, &g1 = o.g1, &g2 = o.g2, &n = o.n;
        const double scale = o.scale;
        const double sa = n.dot(a - g0), sb = n.dot(b - g0), sc = n.dot(c - g0);
        if ((sa >= scale && sb >= scale && sc >= scale) || (sa <= -scale && sb <= -scale && sc <= -scale)) continue;
        // The plane through g's point nearest the centroid, normal to the way there, has all of
        // g (convex) behind it: the triangle's least height above it bounds the distance.
        const Eigen::Vector3d nearest = closest_point_on_triangle(centroid, g0, g1, g2);
        const Eigen::Vector3d away = centroid - nearest;
        const double reach = away.norm();
        if (reach > 0.0 && std::min({away.dot(a - nearest), away.dot(b - nearest), away.dot(c - nearest)}) >= best * reach)
          continue;
        best = std::min(best, triangle_distance(a, b, c, g0, g1, g2));
      }
      deficit[static_cast<std::size_t>(i)] = wall - best;
    }
  };
  pool.run_parts_balanced(kBalancedParts, [&](int part) {
    std::vector<long> run;
    std::vector<OuterFace> nearby;
    Aabb run_box;
    const long count = static_cast<long>(faces.size());
    for (long i = split_point(count, kBalancedParts, part); i < split_point(count, kBalancedParts, part + 1); ++i) {
      const int f = faces[static_cast<std::size_t>(i)];
      const Eigen::Vector3d a = corner(f, 0), b = corner(f, 1), c = corner(f, 2);
      const double longest = std::max({(a - b).norm(), (b - c).norm(), (c - a).norm()});
      const double least = std::min({lower[static_cast<std::size_t>(mesh.F(f, 0))], lower[static_cast<std::size_t>(mesh.F(f, 1))],
                                     lower[static_cast<std::size_t>(mesh.F(f, 2))]});
      if (least - longest * (1.0 + 1e-9) / std::sqrt(3.0) >= wall) continue;
      // A run stays compact (consecutive faces can jump across the cavity between grid rows).
      Aabb grown = run_box;
      grown.extend(face_box(f));
      if (!run.empty() && (run.size() == kRun || (grown.hi - grown.lo).norm() > 2.0 * wall)) {
        measure_run(run, run_box, nearby);
        run.clear();
        grown = face_box(f);
      }
      run.push_back(i);
      run_box = grown;
    }
    if (!run.empty()) measure_run(run, run_box, nearby);
  });
  return deficit;
}


// Distance pass: a candidate stays cavity when d_out >= level. One query per block of 4³ nodes
// decides most of them by the Lipschitz bound. Returns the nodes queried one by one.
std::int64_t keep_nodes_at_level(const TriangleBvh& outer_bvh, const NodeGrid& grid, double level,
                                 std::vector<std::int8_t>& sign, WorkerPool& pool, std::vector<std::int8_t>* queried = nullptr) {
  const std::int64_t bx = (grid.nx + kBlock - 1) / kBlock, by = (grid.ny + kBlock - 1) / kBlock,
                     bz = (grid.nz + kBlock - 1) / kBlock;
  const double rounding = 1e-9 * grid.spacing;  // what a Lipschitz bound gives away to rounding
  std::int64_t per_node[kBalancedParts] = {};
  pool.run_parts_balanced(kBalancedParts, [&](int part) {
    for (std::int64_t kb = split_point(bz, kBalancedParts, part); kb < split_point(bz, kBalancedParts, part + 1); ++kb)
      for (std::int64_t jb = 0; jb < by; ++jb)
        for (std::int64_t ib = 0; ib < bx; ++ib) {
          const std::int64_t i0 = ib * kBlock, j0 = jb * kBlock, k0 = kb * kBlock;
          const std::int64_t i1 = std::min(i0 + kBlock, grid.nx), j1 = std::min(j0 + kBlock, grid.ny),
                             k1 = std::min(k0 + kBlock, grid.nz);
          bool any = false;
          for (std::int64_t k = k0; k < k1 && !any; ++k)
            for (std::int64_t j = j0; j < j1 && !any; ++j)
              for (std::int64_t i = i0; i < i1 && !any; ++i) any = sign[static_cast<std::size_t>(grid.index(i, j, k))] != 0;
          if (!any) continue;
          const Eigen::Vector3d lo(grid.x(i0), grid.y(j0), grid.z(k0)), hi(grid.x(i1 - 1), grid.y(j1 - 1), grid.z(k1 - 1));
          const double half_diagonal = 0.5 * (hi - lo).norm();
          const ClosestPoint centre = closest_point(outer_bvh, 0.5 * (lo + hi), level + half_diagonal);
          if (!centre.found) continue;  // every node of the block is further than the level
          const bool all_near = centre.distance + half_diagonal < level;
          for (std::int64_t k = k0; k < k1; ++k)
            for (std::int64_t j = j0; j < j1; ++j)
              for (std::int64_t i = i0; i < i1; ++i) {
                std::int8_t& s = sign[static_cast<std::size_t>(grid.index(i, j, k))];
                if (!s) continue;
                if (all_near) {
                  s = 0;
                  continue;
                }
                // The centre's exact distance bounds the node's (1-Lipschitz) both ways; only
                // nodes the bounds leave open (by more than rounding) are queried.
                const Eigen::Vector3d node(grid.x(i), grid.y(j), grid.z(k));
                const double r = (node - 0.5 * (lo + hi)).norm();
                if (centre.distance - r >= level + rounding) continue;
                if (centre.distance + r < level - rounding) {
                  s = 0;
                  continue;
                }
                ++per_node[part];
                if (queried) (*queried)[static_cast<std::size_t>(grid.index(i, j, k))] = 1;
                if (face_within(outer_bvh, node, level)) s = 0;
              }
        }
  });
  std::int64_t queried_nodes = 0;
  for (const std::int64_t count : per_node) queried_nodes += count;
  return queried_nodes;
}

// Cells whose nodes disagree, in index order.
std::vector<std::int64_t> mixed_cells(const NodeGrid& grid, const std::vector<std::int8_t>& sign, WorkerPool& pool) {
  std::vector<std::int64_t> cells_part[kParts];
  pool.run_parts(kParts, [&](int part) {
    for (std::int64_t k = split_point(grid.nz - 1, kParts, part); k < split_point(grid.nz - 1, kParts, part + 1); ++k)
      for (std::int64_t j = 0; j + 1 < grid.ny; ++j)
        for (std::int64_t i = 0; i + 1 < grid.nx; ++i) {
          const std::int64_t c = grid.index(i, j, k);
          const std::int8_t s0 = sign[static_cast<std::size_t>(c)];
          bool mixed = false;
          for (int corner = 1; corner < 8 && !mixed; ++corner) {
            const std::int64_t n = c + (corner & 1) + ((corner >> 1) & 1) * grid.nx + ((corner >> 2) & 1) * grid.nx * grid.ny;
            mixed = sign[static_cast<std::size_t>(n)] != s0;
          }
          if (mixed) cells_part[part].push_back(c);
        }
  });
  std::vector<std::int64_t> cells = std::move(cells_part[0]);
  cells.insert(cells.end(), cells_part[1].begin(), cells_part[1].end());
  return cells;
}

// The distances at the nodes of the contoured cells, sorted by node index.
struct NodeValues {
  std::vector<std::int64_t> nodes;
  std::vector<double> outer_distance;  // exact below `level + cap`, else that cap (a lower bound)
  std::vector<double> inner;           // the inner field's signed distance, capped at ±cap
  std::vector<double> phi;             // what marching tetrahedra contours (the sign from the passes)
  std::size_t at(std::int64_t node) const {
    return static_cast<std::size_t>(std::lower_bound(nodes.begin(), nodes.end(), node) - nodes.begin());
  }
};

}  // namespace

// What does not depend on the inner field, kept from one contour for the next on the same outer
// surface, grid and levels (cavity/contour_cavity.h). Every entry is what the contour computed
// for the same inputs, so a contour that reads it is the contour that would have computed it.
struct ContourReuse {
  NodeGrid grid;
  double level = 0.0, target = 0.0;
  std::vector<std::int8_t> outer_winding;
  // Per node, once decided: bit 0 keeps d_out >= level, bit 1 was queried one by one; -1 unknown.
  std::vector<std::int8_t> deep;
  std::vector<std::pair<std::int64_t, double>> outer_distance;  // by node
  // A vertex placed on its edge with these inputs, as the last contour placed it.
  struct Vertex {
    std::int64_t positive = 0, negative = 0;
    double t_in = 0.0, target = 0.0;  // the placement's inputs besides the nodes' distances
    double fraction = 0.0, placed_lower = 0.0;  // the placement (Placement's fields)
    bool on_wall = false;
    bool valid = false;
  };
  std::vector<Vertex> vertices;  // sorted by (positive, negative)

  bool matches(const NodeGrid& g, double level_now, double target_now) const {
    return !outer_winding.empty() && same_grid(g, grid) && level_now == level && target_now == target;
  }
  const Vertex* find(std::int64_t positive, std::int64_t negative) const {
    const auto it = std::lower_bound(vertices.begin(), vertices.end(), std::make_pair(positive, negative),
                                     [](const Vertex& x, const std::pair<std::int64_t, std::int64_t>& key) {
                                       return std::make_pair(x.positive, x.negative) < key;
                                     });
    return it != vertices.end() && it->positive == positive && it->negative == negative && it->valid ? &*it : nullptr;
  }
  bool known_distance(std::int64_t node, double& distance) const {
    const auto it = std::lower_bound(outer_distance.begin(), outer_distance.end(), std::make_pair(node, -kInfinity));
    if (it == outer_distance.end() || it->first != node) return false;
    distance = it->second;
    return true;
  }
  static constexpr double kInfinity = std::numeric_limits<double>::infinity();
};

namespace {

NodeValues node_values(const TriangleBvh& outer_bvh, const InnerField& field, const NodeGrid& grid,
                       const std::vector<std::int64_t>& cells, const std::vector<std::int8_t>& sign,
                       const std::vector<std::int8_t>& outer_winding, const std::vector<std::int8_t>& inner_inside,
                       double target, double level, const NodeValues& previous, const ContourReuse* reuse, WorkerPool& pool) {
  NodeValues v;
  // The cells ascend, so each corner's nodes do: eight ascending lists, joined pairwise by set
  // union (the sorted nodes without repeats, as sorting and dropping repeats would give).
  std::vector<std::int64_t> lists[8];
  static_assert(kParts == 2, "four corners' lists per part");
  pool.run_parts(kParts, [&](int part) {
    for (int corner = 4 * part; corner < 4 * part + 4; ++corner) {
      const std::int64_t offset = (corner & 1) + ((corner >> 1) & 1) * grid.nx + ((corner >> 2) & 1) * grid.nx * grid.ny;
      lists[corner].reserve(cells.size());
      for (const std::int64_t c : cells) lists[corner].push_back(c + offset);
    }
    std::vector<std::int64_t> pair[2];
    for (int k = 0; k < 2; ++k) {
      const std::vector<std::int64_t>&x = lists[4 * part + 2 * k], &y = lists[4 * part + 2 * k + 1];
      std::set_union(x.begin(), x.end(), y.begin(), y.end(), std::back_inserter(pair[k]));
    }
    lists[4 * part].clear();
    std::set_union(pair[0].begin(), pair[0].end(), pair[1].begin(), pair[1].end(), std::back_inserter(lists[4 * part]));
  });
  v.nodes.reserve(lists[0].size() + lists[4].size());
  std::set_union(lists[0].begin(), lists[0].end(), lists[4].begin(), lists[4].end(), std::back_inserter(v.nodes));
  const std::size_t count = v.nodes.size();
  v.outer_distance.resize(count);
  v.inner.resize(count);
  v.phi.resize(count);
  const double h = grid.spacing, cap = 2.0 * h;
  // Nodes are measured by 2³ blocks of the grid. The inner faces within cap of a block's nodes
  // are gathered once per block (FaceShortlist: closest_point's answers; the lists only change
  // the cost). The outer surface is searched from the root, its walk bounded by the distance to
  // the face nearest the block's last node: outer lists (within level + cap) cost more than they
  // saved (bottle: 169 M against 118 M for 28,609 nodes).
  const std::int64_t bx = (grid.nx + 1) / 2, by = (grid.ny + 1) / 2;
  const double half_diagonal = 0.5 * std::sqrt(3.0) * h;
  pool.run_parts(kParts, [&](int part) {
    const long first = split_point(static_cast<long>(count), kParts, part), last = split_point(static_cast<long>(count), kParts, part + 1);
    std::vector<std::pair<std::int64_t, long>> order;  // (block, position in v.nodes)
    order.reserve(static_cast<std::size_t>(last - first));
    for (long n = first; n < last; ++n) {
      const std::int64_t node = v.nodes[static_cast<std::size_t>(n)];
      const std::int64_t i = node % grid.nx, j = (node / grid.nx) % grid.ny, k = node / (grid.nx * grid.ny);
      order.emplace_back(((k / 2) * by + j / 2) * bx + i / 2, n);
    }
    std::sort(order.begin(), order.end());
    FaceShortlist inner_near;
    std::int64_t block = -1;
    bool inner_gathered = false;
    int outer_hint = -1;
    for (const auto& [b, n] : order) {
      if (b != block) {
        block = b;
        inner_gathered = false;
        outer_hint = -1;
      }
      const std::size_t i = static_cast<std::size_t>(n);
      const std::int64_t node = v.nodes[i];
      const std::size_t before = previous.at(node);
      if (before < previous.nodes.size() && previous.nodes[before] == node) {  // measured in an earlier pass
        v.outer_distance[i] = previous.outer_distance[before];
        v.inner[i] = previous.inner[before];
      } else {
        const Eigen::Vector3d p = grid.position(node);
        const std::int64_t bi = b % bx, bj = (b / bx) % by, bk = b / (bx * by);
        const Eigen::Vector3d centre(grid.x(2 * bi) + 0.5 * h, grid.y(2 * bj) + 0.5 * h, grid.z(2 * bk) + 0.5 * h);
        double known = 0.0;
        if (reuse && reuse->known_distance(node, known)) {
          v.outer_distance[i] = known;
        } else {
          const ClosestPoint to_outer = closest_point_hinted(outer_bvh, p, level + cap, outer_hint);
          if (to_outer.found) outer_hint = to_outer.face;
          v.outer_distance[i] = to_outer.found ? to_outer.distance : level + cap;
        }
        if (!inner_gathered) {
          field.gather_near(centre, (cap + half_diagonal) * (1.0 + 1e-6), inner_near);
          inner_gathered = true;
        }
        v.inner[i] = field.signed_distance(p, inner_inside[static_cast<std::size_t>(node)] != 0, cap, &inner_near);
      }
      const double d_out = v.outer_distance[i];
      const double signed_out = outer_winding[static_cast<std::size_t>(node)] >= 1 ? d_out : -d_out;
      double value = std::min(signed_out - target, v.inner[i]);
      if (sign[static_cast<std::size_t>(node)]) value = std::max(value, 0.0);
      else value = std::min(value, -1e-9 * h);
      v.phi[i] = value;
    }
  });
  return v;
}

// φ at the eight corners of every cell (marching_tetrahedra's corner_values). The cells ascend, so
// each corner's node does too: one cursor per corner walks the sorted nodes instead of a binary
// search per corner.
std::vector<double> corner_phi(const NodeGrid& grid, const std::vector<std::int64_t>& cells, const NodeValues& values,
                               WorkerPool& pool) {
  std::vector<double> out(8 * cells.size());
  const std::int64_t nxy = grid.nx * grid.ny;
  pool.run_parts(kParts, [&](int part) {
    const long first = split_point(static_cast<long>(cells.size()), kParts, part),
               last = split_point(static_cast<long>(cells.size()), kParts, part + 1);
    if (first == last) return;
    std::size_t cursor[8];
    std::int64_t offset[8];
    for (int k = 0; k < 8; ++k) {
      offset[k] = (k & 1) + ((k >> 1) & 1) * grid.nx + ((k >> 2) & 1) * nxy;
      cursor[k] = values.at(cells[static_cast<std::size_t>(first)] + offset[k]);
    }
    for (long c = first; c < last; ++c)
      for (int k = 0; k < 8; ++k) {
        const std::int64_t node = cells[static_cast<std::size_t>(c)] + offset[k];
        std::size_t& at = cursor[k];
        while (values.nodes[at] < node) ++at;  // every corner is a listed node
        out[8 * static_cast<std::size_t>(c) + static_cast<std::size_t>(k)] = values.phi[at];
      }
  });
  return out;
}

// What a pass leaves for the next after a demotion: its vertices by their grid edge, and the faces
// (by their vertices' edges) that kept the wall. Away from the demoted nodes the next contour is
// the same, so only what changed is placed and measured again.
struct PassMemory {
  struct Vertex {
    std::int64_t positive = 0, negative = 0;
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    double lower = 0.0, raise = 0.0;
    char on_wall = 0;
    ContourReuse::Vertex placed;  // how it was placed (for ContourReuse)
  };
  std::vector<Vertex> vertices;                          // sorted by (positive, negative)
  std::vector<std::array<std::int64_t, 6>> kept_faces;  // sorted; each face's three edges, sorted

  const Vertex* find(std::int64_t positive, std::int64_t negative) const {
    const auto it = std::lower_bound(vertices.begin(), vertices.end(), std::make_pair(positive, negative),
                                     [](const Vertex& x, const std::pair<std::int64_t, std::int64_t>& key) {
                                       return std::make_pair(x.positive, x.negative) < key;
                                     });
    return it != vertices.end() && it->positive == positive && it->negative == negative ? &*it : nullptr;
  }
};

std::array<std::int64_t, 6> face_key(const TetContour& contour, int f) {
  std::array<std::pair<std::int64_t, std::int64_t>, 3> edges;
  for (int c = 0; c < 3; ++c) {
    const std::size_t v = static_cast<std::size_t>(contour.mesh.F(f, c));
    edges[static_cast<std::size_t>(c)] = {contour.positive_node[v], contour.negative_node[v]};
  }
  std::sort(edges.begin(), edges.end());
  return {edges[0].first, edges[0].second, edges[1].first, edges[1].second, edges[2].first, edges[2].second};
}

// Puts every vertex of the contour on its edge (the inner crossing, or the wall where the outer
// surface binds), then lifts the vertices of faces that dip below the wall between their
// vertices, a few rounds. Returns the faces still below the wall.
std::vector<int> place_vertices(const TriangleBvh& outer_bvh, const InnerField& field, const NodeGrid& grid,
                                const NodeValues& values, double target, double wall, double hair, TetContour& contour,
                                const PassMemory& previous, PassMemory& next, const ContourReuse* reuse,
                                std::vector<ContourReuse::Vertex>* record, WorkerPool& pool, ContourCavity& out) {
  Mesh& mesh = contour.mesh;
  const long vertex_count = static_cast<long>(mesh.V.rows());
  std::vector<double> raise(static_cast<std::size_t>(vertex_count), 0.0), lower(static_cast<std::size_t>(vertex_count));
  std::vector<char> on_wall(static_cast<std::size_t>(vertex_count), 0);
  const double rounding = 1e-9 * grid.spacing;
  const double tolerance = 1e-4 * wall;  // how far above the target a vertex on the wall may sit
  if (record) record->assign(static_cast<std::size_t>(vertex_count), ContourReuse::Vertex());
  auto place = [&](long v, FaceShortlist& near) {
    const std::size_t i = static_cast<std::size_t>(v);
    const std::size_t ip = values.at(contour.positive_node[i]), iq = values.at(contour.negative_node[i]);
    const Eigen::Vector3d p = grid.position(contour.positive_node[i]), q = grid.position(contour.negative_node[i]);
    const double t_in = std::clamp(field.crossing(p, q, values.inner[ip], values.inner[iq]), kMinFraction, 1.0 - kMinFraction);
    const double aim = target + raise[i];
    // The same edge with the same inputs in the last contour (the nodes' distances are the same):
    // its placement, without the distance queries.
    const ContourReuse::Vertex* was = reuse ? reuse->find(contour.positive_node[i], contour.negative_node[i]) : nullptr;
    const Placement placed = was && was->t_in == t_in && was->target == aim
                                 ? Placement{was->fraction, was->placed_lower, was->on_wall}
                                 : place_on_edge(outer_bvh, near, p, q, values.outer_distance[ip], values.outer_distance[iq], t_in,
                                                 aim, tolerance, rounding);
    if (record) {
      ContourReuse::Vertex& r = (*record)[i];
      r.positive = contour.positive_node[i];
      r.negative = contour.negative_node[i];
      r.t_in = t_in;
      r.target = aim;
      r.fraction = placed.fraction;
      r.placed_lower = placed.lower;
      r.on_wall = placed.on_wall;
      r.valid = true;
    }
    mesh.V.row(v) = (p + placed.fraction * (q - p)).transpose();
    lower[i] = placed.lower;
    on_wall[i] = placed.on_wall;
  };
  std::vector<char> remembered(static_cast<std::size_t>(vertex_count), 0);
  pool.run_parts_balanced(kBalancedParts, [&](int part) {
    FaceShortlist near;
    for (long v = split_point(vertex_count, kBalancedParts, part); v < split_point(vertex_count, kBalancedParts, part + 1); ++v) {
      const std::size_t i = static_cast<std::size_t>(v);
      if (const PassMemory::Vertex* was = previous.find(contour.positive_node[i], contour.negative_node[i])) {
        mesh.V.row(v) = was->position.transpose();
        lower[i] = was->lower;
        raise[i] = was->raise;
        on_wall[i] = was->on_wall;
        remembered[i] = 1;
        if (record) (*record)[i] = was->placed;
      } else {
        place(v, near);
      }
    }
  });
  // Faces around each vertex, to check again only what a lift touched.
  std::vector<int> first(static_cast<std::size_t>(vertex_count) + 1, 0), around(static_cast<std::size_t>(3 * mesh.F.rows()));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) ++first[static_cast<std::size_t>(mesh.F(f, c)) + 1];
  for (long v = 0; v < vertex_count; ++v) first[static_cast<std::size_t>(v) + 1] += first[static_cast<std::size_t>(v)];
  {
    std::vector<int> fill(first.begin(), first.end() - 1);
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
      for (int c = 0; c < 3; ++c) around[static_cast<std::size_t>(fill[static_cast<std::size_t>(mesh.F(f, c))]++)] = static_cast<int>(f);
  }
  std::vector<int> check_part[kParts];
  pool.run_parts(kParts, [&](int part) {
    const long face_count = static_cast<long>(mesh.F.rows());
    for (long g = split_point(face_count, kParts, part); g < split_point(face_count, kParts, part + 1); ++g) {
      const int f = static_cast<int>(g);
      const bool known = remembered[static_cast<std::size_t>(mesh.F(f, 0))] && remembered[static_cast<std::size_t>(mesh.F(f, 1))] &&
                         remembered[static_cast<std::size_t>(mesh.F(f, 2))] &&
                         std::binary_search(previous.kept_faces.begin(), previous.kept_faces.end(), face_key(contour, f));
      if (!known) check_part[part].push_back(f);
    }
  });
  std::vector<int> check = std::move(check_part[0]);
  for (int part = 1; part < kParts; ++part) check.insert(check.end(), check_part[part].begin(), check_part[part].end());
  std::vector<int> below;
  for (int round = 0;; ++round) {
    const std::vector<double> deficit = face_deficits(outer_bvh, mesh, lower, check, wall, pool);
    below.clear();
    std::vector<double> lifted = raise;
    for (std::size_t i = 0; i < check.size(); ++i) {
      if (!(deficit[i] > 0.0)) continue;
      below.push_back(check[i]);
      if (round == 0) out.largest_face_deficit = std::max(out.largest_face_deficit, deficit[i]);
      for (int c = 0; c < 3; ++c) {
        const std::size_t v = static_cast<std::size_t>(mesh.F(check[i], c));
        lifted[v] = std::max(lifted[v], raise[v] + 2.0 * deficit[i] + hair);
      }
    }
    if (round == 0 && out.demotions == 0) out.faces_lifted = static_cast<int>(below.size());
    if (below.empty() || round == kRaiseRounds) break;
    std::vector<long> moved;
    for (long v = 0; v < vertex_count; ++v)
      if (lifted[static_cast<std::size_t>(v)] != raise[static_cast<std::size_t>(v)]) moved.push_back(v);
    raise = std::move(lifted);
    pool.run_parts_balanced(kBalancedParts, [&](int part) {
      const long count = static_cast<long>(moved.size());
      FaceShortlist near;
      for (long m = split_point(count, kBalancedParts, part); m < split_point(count, kBalancedParts, part + 1); ++m)
        place(moved[static_cast<std::size_t>(m)], near);
    });
    check.clear();
    for (const long v : moved)
      for (int k = first[static_cast<std::size_t>(v)]; k < first[static_cast<std::size_t>(v) + 1]; ++k) check.push_back(around[static_cast<std::size_t>(k)]);
    std::sort(check.begin(), check.end());
    check.erase(std::unique(check.begin(), check.end()), check.end());
  }
  out.vertices_moved_for_wall = 0;
  for (const char w : on_wall) out.vertices_moved_for_wall += w;

  if (!below.empty()) {  // a demotion follows: remember this pass
    next.vertices.resize(static_cast<std::size_t>(vertex_count));
    for (long v = 0; v < vertex_count; ++v) {
      const std::size_t i = static_cast<std::size_t>(v);
      next.vertices[i] = {contour.positive_node[i], contour.negative_node[i], mesh.V.row(v).transpose(), lower[i], raise[i], on_wall[i],
                          record ? (*record)[i] : ContourReuse::Vertex()};
    }
    sort_in_parts(next.vertices, [](const PassMemory::Vertex& x, const PassMemory::Vertex& y) {
      return std::make_pair(x.positive, x.negative) < std::make_pair(y.positive, y.negative);
    }, pool);
    std::vector<char> failed(static_cast<std::size_t>(mesh.F.rows()), 0);
    for (const int f : below) failed[static_cast<std::size_t>(f)] = 1;
    std::vector<std::array<std::int64_t, 6>> kept_part[kParts];
    pool.run_parts(kParts, [&](int part) {
      const long face_count = static_cast<long>(mesh.F.rows());
      for (long f = split_point(face_count, kParts, part); f < split_point(face_count, kParts, part + 1); ++f)
        if (!failed[static_cast<std::size_t>(f)]) kept_part[part].push_back(face_key(contour, static_cast<int>(f)));
    });
    next.kept_faces = std::move(kept_part[0]);
    for (int part = 1; part < kParts; ++part) next.kept_faces.insert(next.kept_faces.end(), kept_part[part].begin(), kept_part[part].end());
    sort_in_parts(next.kept_faces, std::less<std::array<std::int64_t, 6>>(), pool);
  }
  return below;
}

// Keeps the shells that enclose void of some size: specks are filled, islands join the void.
void keep_shells(const Mesh& mesh, const NodeGrid& grid, double min_shell_fraction, ContourCavity& out) {
  const MeshShells shells = mesh_shells(mesh, grid.origin);
  const std::vector<int>& shell = shells.shell_of_face;
  double total = 0.0;
  for (double v : shells.volume) total += std::max(v, 0.0);
  std::vector<char> keep(shells.volume.size(), 0);
  for (std::size_t s = 0; s < shells.volume.size(); ++s) {
    const double volume = shells.volume[s];
    keep[s] = volume > min_shell_fraction * total && volume > 0.0;
    if (keep[s]) ++out.shells;
    else {
      ++out.shells_dropped;
      out.dropped_volume += volume;
    }
  }
  std::vector<int> new_index(static_cast<std::size_t>(mesh.V.rows()), -1);
  int vertex_count = 0, face_count = 0;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    if (!keep[static_cast<std::size_t>(shell[static_cast<std::size_t>(f)])]) continue;
    ++face_count;
    for (int c = 0; c < 3; ++c) {
      int& index = new_index[static_cast<std::size_t>(mesh.F(f, c))];
      if (index < 0) index = vertex_count++;
    }
  }
  out.cavity.V.resize(vertex_count, 3);
  out.cavity.F.resize(face_count, 3);
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v)
    if (new_index[static_cast<std::size_t>(v)] >= 0) out.cavity.V.row(new_index[static_cast<std::size_t>(v)]) = mesh.V.row(v);
  int row = 0;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    if (!keep[static_cast<std::size_t>(shell[static_cast<std::size_t>(f)])]) continue;
    for (int c = 0; c < 3; ++c) out.cavity.F(row, c) = new_index[static_cast<std::size_t>(mesh.F(f, c))];
    ++row;
  }
}

ContourCavity contour_field(const Mesh& outer, const TriangleBvh& outer_bvh, const InnerField& field,
                            const ContourCavityOptions& options, ContourReuse* reuse = nullptr) {
  ContourCavity out;
  if (const std::string problem = options.check(); !problem.empty()) {
    out.message = problem;
    return out;
  }
  const double wall = options.wall;
  const Aabb outer_box = bounding_box(outer.V);
  const Aabb box = cavity_box(field.box(), outer_box);
  out.ok = true;
  if (box.empty()) return out;  // no void
  NodeGrid& grid = out.grid;
  if (!cavity_grid(box, options.wall, options.cells_per_wall, options.max_nodes, grid)) {
    out.ok = false;
    out.message = "the cavity grid would need more than " + std::to_string(options.max_nodes) + " nodes";
    return out;
  }
  const double h = grid.spacing;
  // Where the outer surface binds, vertices sit at `target`: the wall (plus the margin asked for),
  // and a hair above it that covers rounding to float32 in a written file. Never nearer than
  // 1.01 h: every point of a contoured triangle (diameter <= √2 h, a face diagonal) is within
  // h of one of its vertices, so no triangle then reaches the outer surface, however coarse the
  // node cap makes the grid. Void nodes keep target + kNodeRoom·h (cavity_node_level).
  const double hair = rounding_hair(wall, outer_box);
  const double target = std::max(wall + options.margin_cells * h, 1.01 * h) + hair;
  const double level = cavity_node_level(wall, h, options.margin_cells, outer_box);

  WorkerPool pool(std::max(1, std::min(options.threads, kParts)));
  // Inside the outer surface and inside the inner void: the candidates for the cavity.
  if (reuse && !reuse->matches(grid, level, target)) {
    *reuse = ContourReuse();
    reuse->grid = grid;
    reuse->level = level;
    reuse->target = target;
    reuse->outer_winding = grid_winding(outer, grid, options.threads);
    reuse->deep.assign(static_cast<std::size_t>(grid.node_count()), -1);
  }
  const std::vector<std::int8_t> outer_winding = reuse ? reuse->outer_winding : grid_winding(outer, grid, options.threads);
  const std::vector<std::int8_t> inner_inside = field.inside(grid, outer_winding, options.threads);
  std::vector<std::int8_t> sign(static_cast<std::size_t>(grid.node_count()));  // becomes 1: cavity
  for (std::size_t v = 0; v < sign.size(); ++v) sign[v] = outer_winding[v] >= 1 && inner_inside[v] != 0;
  if (!reuse) {
    out.distance_nodes = keep_nodes_at_level(outer_bvh, grid, level, sign, pool);
  } else {
    // Only the nodes no earlier contour decided; the count is of every node queried for this one.
    std::vector<std::int8_t> open(sign.size()), queried(sign.size(), 0);
    for (std::size_t v = 0; v < sign.size(); ++v) open[v] = sign[v] && reuse->deep[v] < 0;
    keep_nodes_at_level(outer_bvh, grid, level, open, pool, &queried);
    out.distance_nodes = 0;
    for (std::size_t v = 0; v < sign.size(); ++v) {
      if (!sign[v]) continue;
      if (reuse->deep[v] < 0) reuse->deep[v] = static_cast<std::int8_t>(open[v] + 2 * queried[v]);
      sign[v] = reuse->deep[v] & 1;
      out.distance_nodes += reuse->deep[v] >> 1;
    }
  }

  TetContour contour;
  NodeValues values;
  PassMemory memory;
  std::vector<ContourReuse::Vertex> record;
  for (int pass = 0;; ++pass) {
    const std::vector<std::int64_t> cells = mixed_cells(grid, sign, pool);
    out.active_cells = static_cast<std::int64_t>(cells.size());
    values = node_values(outer_bvh, field, grid, cells, sign, outer_winding, inner_inside, target, level, values, reuse, pool);
    contour = marching_tetrahedra(grid, cells, corner_phi(grid, cells, values, pool), kMinFraction, &pool);
    PassMemory next;
    const std::vector<int> below = place_vertices(outer_bvh, field, grid, values, target, wall, hair, contour, memory, next,
                                                  reuse, reuse ? &record : nullptr, pool, out);
    if (reuse) {
      std::vector<std::pair<std::int64_t, double>> measured;
      for (std::size_t i = 0; i < values.nodes.size(); ++i) measured.emplace_back(values.nodes[i], values.outer_distance[i]);
      std::vector<std::pair<std::int64_t, double>> merged;
      std::merge(reuse->outer_distance.begin(), reuse->outer_distance.end(), measured.begin(), measured.end(),
                 std::back_inserter(merged), [](const auto& a, const auto& b) { return a.first < b.first; });
      merged.erase(std::unique(merged.begin(), merged.end(), [](const auto& a, const auto& b) { return a.first == b.first; }),
                   merged.end());
      reuse->outer_distance = std::move(merged);
    }
    memory = std::move(next);
    out.faces_below_wall = static_cast<int>(below.size());
    if (below.empty() || pass == kDemotions) break;
    // Faces that no lift along their edges brought to the wall: their void nodes become material.
    for (const int f : below)
      for (int c = 0; c < 3; ++c) sign[static_cast<std::size_t>(contour.positive_node[static_cast<std::size_t>(contour.mesh.F(f, c))])] = 0;
    ++out.demotions;
  }
  if (reuse) {  // the last pass's placements, by edge, for the next contour
    std::vector<std::pair<std::pair<std::int64_t, std::int64_t>, std::size_t>> order;
    order.reserve(record.size());
    for (std::size_t v = 0; v < record.size(); ++v)
      if (record[v].valid) order.push_back({{record[v].positive, record[v].negative}, v});
    std::sort(order.begin(), order.end());
    reuse->vertices.clear();
    reuse->vertices.reserve(order.size());
    for (const auto& entry : order) reuse->vertices.push_back(record[entry.second]);
  }
  keep_shells(contour.mesh, grid, options.min_shell_fraction, out);
  return out;
}

}  // namespace

bool cavity_grid(const Aabb& box, double wall, double cells_per_wall, std::int64_t max_nodes, NodeGrid& grid) {
  double h = wall / cells_per_wall;
  const Eigen::Vector3d extent = box.hi - box.lo;
  auto nodes_for = [&](double spacing) {
    double count = 1.0;
    for (int a = 0; a < 3; ++a) count *= std::ceil(extent(a) / spacing) + 6.0;
    return count;
  };
  for (int grow = 0; grow < 60 && nodes_for(h) > static_cast<double>(max_nodes); ++grow) h *= 1.05;
  if (nodes_for(h) > static_cast<double>(max_nodes)) return false;
  grid.spacing = h;
  // Offsets by odd fractions of h: grid rows and nodes then miss the round coordinates of CAD
  // meshes (the tie-breaking in grid_winding makes such hits correct anyway, but rarer is cheaper).
  grid.origin = box.lo - Eigen::Vector3d(2.2371, 2.3119, 2.4243) * h;
  grid.nx = static_cast<std::int64_t>(std::ceil(extent.x() / h)) + 6;
  grid.ny = static_cast<std::int64_t>(std::ceil(extent.y() / h)) + 6;
  grid.nz = static_cast<std::int64_t>(std::ceil(extent.z() / h)) + 6;
  return true;
}

Aabb cavity_box(const Aabb& void_box, const Aabb& outer_box) {
  Aabb box = void_box;
  box.lo = box.lo.cwiseMax(outer_box.lo);
  box.hi = box.hi.cwiseMin(outer_box.hi);
  return box;
}

double cavity_node_level(double wall, double h, double margin_cells, const Aabb& outer_box) {
  return std::max(wall + margin_cells * h, 1.01 * h) + rounding_hair(wall, outer_box) + kNodeRoom * h;
}

std::string ContourCavityOptions::check() const {
  const ContourCavityOptions& o = *this;
  if (!(o.wall > 0.0) || !std::isfinite(o.wall)) return "the wall must be > 0";
  if (!(o.cells_per_wall >= 1.25 && o.cells_per_wall <= 8.0)) return "cells per wall must be in [1.25, 8]";
  if (!(o.margin_cells >= 0.0 && o.margin_cells <= 2.0)) return "the margin must be in [0, 2] cells";
  if (o.max_nodes < 1000) return "the node cap must be >= 1000";
  if (!(o.min_shell_fraction >= 0.0 && o.min_shell_fraction < 1.0)) return "the shell fraction must be in [0, 1)";
  if (o.threads < 1 || o.threads > 64) return "threads must be in [1, 64]";
  return "";
}

ContourCavity contour_cavity(const Mesh& outer, const TriangleBvh& outer_bvh, const Mesh& inner,
                             const ContourCavityOptions& options, const GridWinding* inner_winding) {
  if (inner.F.rows() == 0) {  // no void
    ContourCavity out;
    out.message = options.check();
    out.ok = out.message.empty();
    return out;
  }
  return contour_field(outer, outer_bvh, MeshField(inner, inner_winding), options);
}

ContourCavity contour_cavity(const Mesh& outer, const TriangleBvh& outer_bvh, const Vector10d& quadric,
                             const ContourCavityOptions& options, std::shared_ptr<ContourReuse>* reuse) {
  if (!quadric.allFinite()) {
    ContourCavity out;
    out.message = "the quadric's coefficients must be finite";
    return out;
  }
  if (reuse && !*reuse) *reuse = std::make_shared<ContourReuse>();
  return contour_field(outer, outer_bvh, QuadricField(quadric, bounding_box(outer.V)), options, reuse ? reuse->get() : nullptr);
}

}  // namespace offsetopt
