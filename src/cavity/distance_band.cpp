#include "cavity/distance_band.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "geometry/aabb.h"
#include "geometry/closest_point.h"
#include "util/parallel.h"

namespace offsetopt {

namespace {

constexpr int kBlock = 4;  // points per block side in the point pass
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

// BandMethod::automatic's choice (distance_band.h). Instructions of the carvable cells by points
// against by faces (callgrind, --threads 1) and the tests per masked point: sphere 250 -> 195 M
// (2.4 tests), buoy 219 -> 178 (3.6), roly-poly 219 -> 174 (4.0), top 185 -> 148 (6.1), bottle
// `stand` 145 -> 121 (8.1), bottle `stand-filled --outer`, five thresholds up to 3.9 h, 643 -> 959
// (9.7): the cut sits between the last two.
constexpr std::int64_t kFacePassPoints = std::int64_t{1} << 22;
constexpr double kFacePassTestsPerPoint = 8.5;

// The points of `g` whose coordinates along one axis lie within [lo, hi] (clamped to the grid),
// widened by 1e-9 of a step against the rounding of the division (a wider range only costs tests).
std::pair<std::int64_t, std::int64_t> index_range(double lo, double hi, double origin, double h, std::int64_t n) {
  const double a = std::ceil((lo - origin) / h - 1e-9), b = std::floor((hi - origin) / h + 1e-9);
  return {static_cast<std::int64_t>(std::max(0.0, a)), static_cast<std::int64_t>(std::min(static_cast<double>(n - 1), b))};
}

// BandMethod::by_faces. A face farther than every threshold from a point changes nothing for it,
// and sqrt(min) = min(sqrt) (a correctly rounded root is monotone), so each point reaches exactly
// the thresholds face_within(bvh, p, t, true) says it does. Each part owns a slab of z: the same
// result for any thread count.
std::vector<std::int8_t> distance_band_by_faces(const NodeGrid& g, const std::vector<std::int8_t>& mask, const TriangleBvh& bvh,
                                                const std::vector<double>& thresholds, WorkerPool& pool) {
  const double top = thresholds.back();
  const double reach = top * (1.0 + 1e-9);
  const double reach_squared = reach * reach;
  std::vector<double> least(static_cast<std::size_t>(g.node_count()), kInf);
  const int face_count = static_cast<int>(bvh.faces().rows());
  pool.run_parts(kParts, [&](int part) {
    const std::int64_t k_begin = split_point(g.nz, kParts, part), k_end = split_point(g.nz, kParts, part + 1);
    for (int f = 0; f < face_count; ++f) {
      const Aabb& box = bvh.face_box(f);
      const auto [i0, i1] = index_range(box.lo.x() - reach, box.hi.x() + reach, g.origin.x(), g.spacing, g.nx);
      const auto [j0, j1] = index_range(box.lo.y() - reach, box.hi.y() + reach, g.origin.y(), g.spacing, g.ny);
      auto [k0, k1] = index_range(box.lo.z() - reach, box.hi.z() + reach, g.origin.z(), g.spacing, g.nz);
      k0 = std::max(k0, k_begin);
      k1 = std::min(k1, k_end - 1);
      const Eigen::Vector3d a = bvh.corner(f, 0), b = bvh.corner(f, 1), c = bvh.corner(f, 2);
      for (std::int64_t k = k0; k <= k1; ++k)
        for (std::int64_t j = j0; j <= j1; ++j)
          for (std::int64_t i = i0; i <= i1; ++i) {
            const std::size_t v = static_cast<std::size_t>(g.index(i, j, k));
            if (!mask[v]) continue;
            const Eigen::Vector3d p(g.x(i), g.y(j), g.z(k));
            if (box.squared_distance(p) > reach_squared) continue;
            const double squared = (closest_point_on_triangle(p, a, b, c) - p).squaredNorm();
            if (squared < least[v]) least[v] = squared;
          }
    }
  });
  std::vector<std::int8_t> band(static_cast<std::size_t>(g.node_count()), 0);
  const int count = static_cast<int>(thresholds.size());
  for (std::size_t v = 0; v < band.size(); ++v) {
    if (!mask[v]) continue;
    const double d = std::sqrt(least[v]);
    int reached = 0;
    while (reached < count && !(d < thresholds[static_cast<std::size_t>(reached)])) ++reached;
    band[v] = static_cast<std::int8_t>(reached);
  }
  return band;
}

// The point-face tests distance_band_by_faces would make (each face's grown box, clamped).
double face_pass_tests(const NodeGrid& g, const TriangleBvh& bvh, double top) {
  const double reach = top * (1.0 + 1e-9);
  double tests = 0.0;
  for (int f = 0; f < static_cast<int>(bvh.faces().rows()); ++f) {
    const Aabb& box = bvh.face_box(f);
    const auto [i0, i1] = index_range(box.lo.x() - reach, box.hi.x() + reach, g.origin.x(), g.spacing, g.nx);
    const auto [j0, j1] = index_range(box.lo.y() - reach, box.hi.y() + reach, g.origin.y(), g.spacing, g.ny);
    const auto [k0, k1] = index_range(box.lo.z() - reach, box.hi.z() + reach, g.origin.z(), g.spacing, g.nz);
    if (i1 < i0 || j1 < j0 || k1 < k0) continue;
    tests += static_cast<double>(i1 - i0 + 1) * static_cast<double>(j1 - j0 + 1) * static_cast<double>(k1 - k0 + 1);
  }
  return tests;
}

}  // namespace

std::vector<std::int8_t> distance_band(const NodeGrid& g, const std::vector<std::int8_t>& mask, const TriangleBvh& bvh,
                                       const std::vector<double>& thresholds, int threads, std::int64_t& queries,
                                       BandMethod method) {
  if (thresholds.empty()) return std::vector<std::int8_t>(static_cast<std::size_t>(g.node_count()), 0);
  const int k = static_cast<int>(thresholds.size());
  const double top = thresholds.back();
  const double rounding = 1e-9 * g.spacing;
  auto count_below = [&](double d) {
    int c = 0;
    while (c < k && thresholds[static_cast<std::size_t>(c)] <= d) ++c;
    return static_cast<std::int8_t>(c);
  };
  WorkerPool pool(std::max(1, std::min(threads, kParts)));
  if (method == BandMethod::automatic && g.node_count() <= kFacePassPoints && !bvh.empty()) {
    std::int64_t masked = 0;
    for (const std::int8_t m : mask) masked += m != 0;
    if (face_pass_tests(g, bvh, top) <= kFacePassTestsPerPoint * static_cast<double>(masked)) method = BandMethod::by_faces;
  }
  if (method == BandMethod::by_faces && !bvh.empty()) return distance_band_by_faces(g, mask, bvh, thresholds, pool);
  std::vector<std::int8_t> band(static_cast<std::size_t>(g.node_count()), 0);
  const std::int64_t bx = (g.nx + kBlock - 1) / kBlock, by = (g.ny + kBlock - 1) / kBlock, bz = (g.nz + kBlock - 1) / kBlock;
  std::int64_t per_part[kParts] = {0, 0};
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


}  // namespace offsetopt
