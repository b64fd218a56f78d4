#include "cavity/carvable_cells.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cavity/contour_cavity.h"
#include "geometry/aabb.h"
#include "geometry/closest_point.h"
#include "geometry/grid_winding.h"
#include "util/parallel.h"

namespace offsetopt {

namespace {

constexpr int kBlock = 4;  // points per block side in the distance passes
constexpr int kParts = 2;  // every parallel loop is cut into this many fixed parts
constexpr double kInf = std::numeric_limits<double>::infinity();

// The faces whose own box lies within `radius` of p (a superset of those within radius).
void faces_near(const TriangleBvh& bvh, const Eigen::Vector3d& p, double radius, std::vector<int>& out) {
  out.clear();
  const double limit = radius * radius;
  bvh.traverse([&](const Aabb& box) { return box.squared_distance(p) <= limit; },
               [&](int face) {
                 if (bvh.face_box(face).squared_distance(p) <= limit) out.push_back(face);
                 return true;
               });
}

// The distance from p to the nearest of `faces`, +inf when there is none; or, as soon as one face
// is nearer than `enough`, that face's distance (all the caller needs to know then). `hint` (a face
// near p, or -1) is measured first, and faces whose box lies beyond the best so far, or beyond
// `bound` (an upper bound on the answer), are skipped unseen; should none lie within the bound
// after all, the search runs again unbounded.
double nearest_of(const TriangleBvh& bvh, const std::vector<int>& faces, const Eigen::Vector3d& p, double bound, double enough,
                  int hint) {
  double best = bound * bound;
  const double enough_squared = enough > 0.0 ? enough * enough : -1.0;
  bool found = false;
  auto measure = [&](int face) {
    if (bvh.face_box(face).squared_distance(p) > best) return;
    const Eigen::Vector3d q = closest_point_on_triangle(p, bvh.corner(face, 0), bvh.corner(face, 1), bvh.corner(face, 2));
    const double squared = (q - p).squaredNorm();
    if (squared < best) {
      best = squared;
      found = true;
    }
  };
  if (hint >= 0) measure(hint);
  for (std::size_t f = 0; f < faces.size() && !(best < enough_squared); ++f)
    if (faces[f] != hint) measure(faces[f]);
  if (!found) return bound == kInf ? kInf : nearest_of(bvh, faces, p, kInf, enough, -1);
  return std::sqrt(best);
}

// Per point of `g` where mask != 0: how many of the ascending `thresholds` its unsigned distance to
// the surface reaches (d >= t, as face_within decides it). One capped query per block of 4³ points:
// its centre's distance D and closest point q bound every point's distance, d(p) >= D − |p − c| and
// d(p) <= min(D + |p − c|, |p − q|), which settle most points (all of a block no threshold comes
// near). A 2³ sub-block with points left open gathers the faces that can be nearest to any of its
// points (within u + 2 r2 of its centre c2, u bounding d(c2), r2 its half diagonal; or within
// top + r2 when that is less: a point with no face that near reaches every threshold), and each
// open point's distance is the least over them. Every margin is `rounding`, far above the
// computed distances' errors; a distance within it of a threshold is decided by face_within itself.
std::vector<std::int8_t> distance_band(const NodeGrid& g, const std::vector<std::int8_t>& mask, const TriangleBvh& bvh,
                                       const std::vector<double>& thresholds, int threads, std::int64_t& queries) {
  std::vector<std::int8_t> band(static_cast<std::size_t>(g.node_count()), 0);
  if (thresholds.empty()) return band;
  const int k = static_cast<int>(thresholds.size());
  const double top = thresholds.back();
  const double rounding = 1e-9 * g.spacing;
  auto count_below = [&](double d) {
    int c = 0;
    while (c < k && thresholds[static_cast<std::size_t>(c)] <= d) ++c;
    return static_cast<std::int8_t>(c);
  };
  const std::int64_t bx = (g.nx + kBlock - 1) / kBlock, by = (g.ny + kBlock - 1) / kBlock, bz = (g.nz + kBlock - 1) / kBlock;
  std::int64_t per_part[kParts] = {0, 0};
  WorkerPool pool(std::max(1, std::min(threads, kParts)));
  pool.run_parts(kParts, [&](int part) {
    std::vector<int> candidates;
    for (std::int64_t kb = split_point(bz, kParts, part); kb < split_point(bz, kParts, part + 1); ++kb)
      for (std::int64_t jb = 0; jb < by; ++jb)
        for (std::int64_t ib = 0; ib < bx; ++ib) {
          const std::int64_t i0 = ib * kBlock, j0 = jb * kBlock, k0 = kb * kBlock;
          const std::int64_t i1 = std::min(i0 + kBlock, g.nx), j1 = std::min(j0 + kBlock, g.ny), k1 = std::min(k0 + kBlock, g.nz);
          bool any = false;
          for (std::int64_t kk = k0; kk < k1 && !any; ++kk)
            for (std::int64_t j = j0; j < j1 && !any; ++j)
              for (std::int64_t i = i0; i < i1 && !any; ++i) any = mask[static_cast<std::size_t>(g.index(i, j, kk))] != 0;
          if (!any) continue;
          const Eigen::Vector3d lo(g.x(i0), g.y(j0), g.z(k0)), hi(g.x(i1 - 1), g.y(j1 - 1), g.z(k1 - 1));
          const Eigen::Vector3d mid = 0.5 * (lo + hi);
          const double half_diagonal = 0.5 * (hi - lo).norm();
          const ClosestPoint c = closest_point(bvh, mid, top + half_diagonal + g.spacing);
          const double D = c.found ? c.distance : kInf;
          const std::int8_t block_low = count_below(D - half_diagonal - rounding);
          if (block_low == count_below(D + half_diagonal + rounding)) {
            for (std::int64_t kk = k0; kk < k1; ++kk)
              for (std::int64_t j = j0; j < j1; ++j)
                for (std::int64_t i = i0; i < i1; ++i) {
                  const std::size_t v = static_cast<std::size_t>(g.index(i, j, kk));
                  if (mask[v]) band[v] = block_low;
                }
            continue;
          }
          for (std::int64_t sk = k0; sk < k1; sk += 2)
            for (std::int64_t sj = j0; sj < j1; sj += 2)
              for (std::int64_t si = i0; si < i1; si += 2) {
                const std::int64_t si1 = std::min(si + 2, i1), sj1 = std::min(sj + 2, j1), sk1 = std::min(sk + 2, k1);
                const Eigen::Vector3d sub_lo(g.x(si), g.y(sj), g.z(sk)), sub_hi(g.x(si1 - 1), g.y(sj1 - 1), g.z(sk1 - 1));
                const Eigen::Vector3d sub_mid = 0.5 * (sub_lo + sub_hi);
                const double sub_half_diagonal = 0.5 * (sub_hi - sub_lo).norm();
                bool gathered = false;
                for (std::int64_t kk = sk; kk < sk1; ++kk)
                  for (std::int64_t j = sj; j < sj1; ++j)
                    for (std::int64_t i = si; i < si1; ++i) {
                      const std::size_t v = static_cast<std::size_t>(g.index(i, j, kk));
                      if (!mask[v]) continue;
                      const Eigen::Vector3d p(g.x(i), g.y(j), g.z(kk));
                      const double r = (p - mid).norm();
                      double upper = D + r;
                      if (c.found) upper = std::min(upper, (p - c.point).norm());
                      const std::int8_t low = count_below(D - r - rounding), high = count_below(upper + rounding);
                      if (low >= high) {
                        band[v] = low;
                        continue;
                      }
                      if (!gathered) {
                        double centre_upper = D + (sub_mid - mid).norm();
                        if (c.found) centre_upper = std::min(centre_upper, (sub_mid - c.point).norm());
                        const double reach = std::min(centre_upper + sub_half_diagonal, top) + rounding;
                        faces_near(bvh, sub_mid, reach + sub_half_diagonal + rounding, candidates);
                        gathered = true;
                      }
                      // Only the thresholds in [low, high) are open, lowest first (d >= t for a
                      // threshold implies it for the lower ones).
                      ++per_part[part];
                      const double d = nearest_of(bvh, candidates, p, upper + rounding, thresholds[static_cast<std::size_t>(low)] - rounding, c.face);
                      std::int8_t reached = low;
                      while (reached < high) {
                        const double t = thresholds[static_cast<std::size_t>(reached)];
                        if (d < t - rounding) break;
                        if (d <= t + rounding && face_within(bvh, p, t, true)) break;
                        ++reached;
                      }
                      band[v] = reached;
                    }
              }
        }
  });
  queries += per_part[0] + per_part[1];
  return band;
}

}  // namespace

std::string CarvableCellsOptions::check() const {
  const CarvableCellsOptions& o = *this;
  if (!(o.wall > 0.0) || !std::isfinite(o.wall)) return "the wall must be > 0";
  if (!(o.cells_per_wall >= 1.25 && o.cells_per_wall <= 8.0)) return "cells per wall must be in [1.25, 8]";
  if (!(o.margin_cells >= 0.0 && o.margin_cells <= 2.0)) return "the margin must be in [0, 2] cells";
  if (o.max_nodes < 1000) return "the node cap must be >= 1000";
  if (o.band && (!(o.outer_max > 0.0) || !std::isfinite(o.outer_max))) return "the band needs outer_max > 0";
  if (o.band && (!(o.ground_tol >= 0.0) || !std::isfinite(o.ground_z))) return "the band needs a ground and ground_tol >= 0";
  if (o.threads < 1 || o.threads > 64) return "threads must be in [1, 64]";
  return "";
}

Eigen::Vector3d CarvableCells::centre(std::int64_t cell) const {
  const double half = 0.5 * grid.spacing;
  return grid.position(cell) + Eigen::Vector3d(half, half, half);
}

Eigen::Vector3d CarvableCells::centre(std::int64_t i, std::int64_t j, std::int64_t k) const {
  const double half = 0.5 * grid.spacing;
  return grid.position(i, j, k) + Eigen::Vector3d(half, half, half);
}

Vector10d cube_integrals(const Eigen::Vector3d& centre, double h, const Eigen::Vector3d& origin) {
  const Eigen::Vector3d p = centre - origin;
  const double v = h * h * h, s = h * h / 12.0;
  Vector10d out;
  out << v, v * p.x(), v * p.y(), v * p.z(), v * (p.x() * p.x() + s), v * (p.y() * p.y() + s), v * (p.z() * p.z() + s),
      v * p.x() * p.y(), v * p.y() * p.z(), v * p.z() * p.x();
  return out;
}

CarvableCells carvable_cells(const Mesh& outer, const TriangleBvh& outer_bvh, const CarvableCellsOptions& options) {
  CarvableCells out;
  if (const std::string problem = options.check(); !problem.empty()) {
    out.message = problem;
    return out;
  }
  const double wall = options.wall;
  Aabb box = bounding_box(outer.V);
  if (box.empty()) {
    out.message = "the mesh has no vertex";
    return out;
  }
  if (options.band) {
    box.lo -= Eigen::Vector3d::Constant(options.outer_max);
    box.hi += Eigen::Vector3d::Constant(options.outer_max);
  }
  // The contour's grid and node test (cavity/contour_cavity.h), so the inner cells are ones it
  // can write whole.
  NodeGrid& grid = out.grid;
  if (!cavity_grid(box, wall, options.cells_per_wall, options.max_nodes, grid)) {
    out.message = "the cell grid would need more than " + std::to_string(options.max_nodes) + " nodes";
    return out;
  }
  const double h = grid.spacing;
  out.margin = options.node_margin >= 0.0 ? options.node_margin
                                          : cavity_node_level(wall, h, options.margin_cells, bounding_box(outer.V)) - wall;
  NodeGrid centres;
  centres.spacing = h;
  centres.origin = grid.origin + Eigen::Vector3d::Constant(0.5 * h);
  centres.nx = grid.nx - 1;
  centres.ny = grid.ny - 1;
  centres.nz = grid.nz - 1;

  // Nodes: inside with distance >= wall + margin (the contour's cavity nodes).
  std::vector<std::int8_t> deep;
  if (options.strict) {
    const std::vector<std::int8_t> node_winding = grid_winding(outer, grid, options.threads);
    std::vector<std::int8_t> node_inside(node_winding.size());
    for (std::size_t v = 0; v < node_winding.size(); ++v) node_inside[v] = node_winding[v] >= 1;
    deep = distance_band(grid, node_inside, outer_bvh, {wall + out.margin}, options.threads, out.distance_queries);
  }

  // Centres: the thresholds every reading needs, each answered by one band count.
  const double r = 0.5 * std::sqrt(3.0) * h;
  const double level = wall - r - (options.band ? options.outer_max : 0.0);  // signed, outer void cells
  std::vector<double> thresholds;
  if (level > 0.0) thresholds.push_back(level);
  if (level < 0.0) thresholds.push_back(-level);
  thresholds.push_back(wall);  // the mid reading
  if (options.band) {
    thresholds.push_back(r);
    thresholds.push_back(options.outer_max);
    thresholds.push_back(options.outer_max + r);
  }
  std::sort(thresholds.begin(), thresholds.end());
  thresholds.erase(std::unique(thresholds.begin(), thresholds.end()), thresholds.end());
  const std::vector<std::int8_t> centre_winding = grid_winding(outer, centres, options.threads);
  std::vector<std::int8_t> centre_mask(centre_winding.size());
  const bool outside_matters = options.band || level < 0.0;
  for (std::size_t v = 0; v < centre_winding.size(); ++v) centre_mask[v] = centre_winding[v] >= 1 || outside_matters;
  const std::vector<std::int8_t> centre_band =
      distance_band(centres, centre_mask, outer_bvh, thresholds, options.threads, out.distance_queries);
  // d >= t for one of the thresholds (by its position in the sorted list).
  // Positions looked up once (a threshold not in the list is never asked about).
  auto position = [&](double t) {
    return static_cast<std::int8_t>(std::lower_bound(thresholds.begin(), thresholds.end(), t) - thresholds.begin());
  };
  const std::int8_t at_level = position(level), at_minus_level = position(-level), at_wall = position(wall),
                    at_r = position(r), at_outer = position(options.outer_max), at_outer_r = position(options.outer_max + r);
  auto reaches = [&](std::size_t v, std::int8_t at) { return centre_band[v] > at; };
  const bool outside_listed = options.band || level < 0.0 || options.strict;

  const double base = options.ground_z + 2.0 * options.outer_max + options.ground_tol;
  std::vector<std::int64_t> lists[kParts][6];
  WorkerPool pool(std::max(1, std::min(options.threads, kParts)));
  pool.run_parts(kParts, [&](int part) {
    const std::int64_t nxy = grid.nx * grid.ny;
    for (std::int64_t k = split_point(centres.nz, kParts, part); k < split_point(centres.nz, kParts, part + 1); ++k)
      for (std::int64_t j = 0; j < centres.ny; ++j)
        for (std::int64_t i = 0; i < centres.nx; ++i) {
          const std::size_t c = static_cast<std::size_t>(centres.index(i, j, k));
          const bool inside = centre_winding[c] >= 1;
          if (!inside && !outside_listed) continue;
          const std::int64_t cell = grid.index(i, j, k);
          bool whole = options.strict;
          for (int corner = 0; corner < 8 && whole; ++corner)
            whole = deep[static_cast<std::size_t>(cell + (corner & 1) + ((corner >> 1) & 1) * grid.nx + ((corner >> 2) & 1) * nxy)] > 0;
          const bool may = whole || (inside ? (level <= 0.0 || reaches(c, at_level)) : (level < 0.0 && !reaches(c, at_minus_level)));
          if (whole) lists[part][0].push_back(cell);
          if (may) lists[part][1].push_back(cell);
          if (inside && reaches(c, at_wall)) lists[part][5].push_back(cell);
          if (!options.band) continue;
          const double z = centres.z(k);
          if (!inside && !reaches(c, at_outer) && z - 0.5 * h >= base)
            lists[part][2].push_back(cell);
          const bool above_contacts = z + 0.5 * h > options.ground_z + options.ground_tol;
          if ((inside ? !reaches(c, at_r) : !reaches(c, at_outer_r)) && above_contacts) lists[part][3].push_back(cell);
          if (inside && !reaches(c, at_outer_r) && above_contacts) lists[part][4].push_back(cell);
        }
  });
  std::vector<std::int64_t>* targets[6] = {&out.inner, &out.outer, &out.band_inner, &out.band_outer, &out.skin_outer, &out.mid};
  for (int l = 0; l < 6; ++l) {
    targets[l]->swap(lists[0][l]);
    for (int part = 1; part < kParts; ++part) targets[l]->insert(targets[l]->end(), lists[part][l].begin(), lists[part][l].end());
  }
  out.ok = true;
  return out;
}

}  // namespace offsetopt
