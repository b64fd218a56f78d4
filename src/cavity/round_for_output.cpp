#include "cavity/round_for_output.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <utility>

#include "geometry/bvh.h"
#include "geometry/exact_triangle_intersection.h"
#include "geometry/faces_intersect_exact.h"
#include "geometry/intersecting_faces.h"

namespace offsetopt {

namespace {

using Pair = std::pair<int, int>;
constexpr std::size_t kPairCap = kRoundingPairCap;

double nearest_float(double x) { return static_cast<double>(static_cast<float>(x)); }

// The float `steps` float32 ulps away from the float nearest to x.
double float_steps(double x, int steps) {
  float f = static_cast<float>(x);
  for (int s = 0; s < std::abs(steps); ++s) f = std::nextafter(f, steps > 0 ? HUGE_VALF : -HUGE_VALF);
  return static_cast<double>(f);
}

double largest_coordinate(const Mesh& mesh) { return mesh.V.size() ? mesh.V.cwiseAbs().maxCoeff() : 0.0; }

// The ulp of float32 numbers of magnitude up to `magnitude` (an upper bound).
double float_ulp(double magnitude) { return std::ldexp(std::max(magnitude, 1e-30), -23); }

// Per-coordinate ulp offsets to try, fewest ulps first, then in a fixed order.
std::vector<std::array<int, 3>> candidate_offsets() {
  std::vector<std::array<int, 3>> out;
  const int n = kRoundingSearchUlps;
  for (int x = -n; x <= n; ++x)
    for (int y = -n; y <= n; ++y)
      for (int z = -n; z <= n; ++z) out.push_back({x, y, z});
  std::stable_sort(out.begin(), out.end(), [](const std::array<int, 3>& a, const std::array<int, 3>& b) {
    return std::abs(a[0]) + std::abs(a[1]) + std::abs(a[2]) < std::abs(b[0]) + std::abs(b[1]) + std::abs(b[2]);
  });
  return out;
}

class Repair {
 public:
  // `reference` pairs: those the unrounded mesh already has (sorted); they are not new.
  Repair(const Mesh& original, Mesh& rounded, std::vector<char> frozen, std::vector<Pair> reference, int threads)
      : original_(original), mesh_(rounded), frozen_(std::move(frozen)), reference_(std::move(reference)), threads_(threads) {
    const Eigen::Index nv = mesh_.V.rows(), nf = mesh_.F.rows();
    first_.assign(static_cast<std::size_t>(nv) + 1, 0);
    for (Eigen::Index f = 0; f < nf; ++f)
      for (int c = 0; c < 3; ++c) ++first_[static_cast<std::size_t>(mesh_.F(f, c)) + 1];
    for (std::size_t v = 0; v < static_cast<std::size_t>(nv); ++v) first_[v + 1] += first_[v];
    incident_.resize(static_cast<std::size_t>(3 * nf));
    std::vector<int> fill(first_.begin(), first_.end() - 1);
    for (Eigen::Index f = 0; f < nf; ++f)
      for (int c = 0; c < 3; ++c) incident_[static_cast<std::size_t>(fill[static_cast<std::size_t>(mesh_.F(f, c))]++)] = static_cast<int>(f);
    was_collinear_.assign(static_cast<std::size_t>(nf), -1);
    slack_ = 4.0 * (2 * kRoundingSearchUlps + 1) * float_ulp(largest_coordinate(original));
  }

  // New defects (pairs and collinear faces) of the mesh as it is now; `found` gets its pairs and
  // `tree` the tree they were searched in.
  long long new_defects(std::vector<int>* faces, IntersectingFaces& found, std::shared_ptr<const TriangleBvh>& tree) const {
    tree = std::make_shared<const TriangleBvh>(mesh_.V, mesh_.F, tree_options());
    // Which faces are collinear, from the tree's copy of the corners: the search needs it too.
    std::vector<char> flat(static_cast<std::size_t>(mesh_.F.rows()));
    for (Eigen::Index f = 0; f < mesh_.F.rows(); ++f) {
      const int face = static_cast<int>(f);
      flat[static_cast<std::size_t>(f)] = collinear_exact(tree->corner(face, 0), tree->corner(face, 1), tree->corner(face, 2)) ? 1 : 0;
    }
    found = self_intersections_in_parts(*tree, kPairCap, threads_, &flat);
    long long count = 0;
    for (const Pair& p : found.pairs)
      if (!std::binary_search(reference_.begin(), reference_.end(), p)) {
        ++count;
        if (faces) faces->insert(faces->end(), {p.first, p.second});
      }
    for (Eigen::Index f = 0; f < mesh_.F.rows(); ++f)
      if (flat[static_cast<std::size_t>(f)] && !was_collinear(static_cast<int>(f))) {
        ++count;
        if (faces) faces->push_back(static_cast<int>(f));
      }
    return count;
  }

  // One pass over the corners of `faces`: each moves to the candidate with the fewest new
  // defects around it. Returns whether any vertex moved.
  bool pass(const std::vector<int>& faces) {
    std::vector<int> vertices;
    for (const int f : faces)
      for (int c = 0; c < 3; ++c) vertices.push_back(mesh_.F(f, c));
    std::sort(vertices.begin(), vertices.end());
    vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
    bvh_ = TriangleBvh(mesh_.V, mesh_.F, tree_options());
    static const std::vector<std::array<int, 3>> offsets = candidate_offsets();
    bool moved = false;
    for (const int v : vertices) {
      if (!frozen_.empty() && frozen_[static_cast<std::size_t>(v)]) continue;
      const Eigen::Vector3d p = original_.V.row(v).transpose(), current = mesh_.V.row(v).transpose();
      Eigen::Vector3d best = current;
      long long fewest = local_defects(v, current);
      for (const auto& o : offsets) {
        if (fewest == 0) break;
        const Eigen::Vector3d x(float_steps(p.x(), o[0]), float_steps(p.y(), o[1]), float_steps(p.z(), o[2]));
        const long long d = local_defects(v, x);
        if (d < fewest) {
          fewest = d;
          best = x;
        }
      }
      if (best != current) {
        mesh_.V.row(v) = best.transpose();
        moved = true;
      }
    }
    return moved;
  }

 private:
  BvhOptions tree_options() const {
    BvhOptions options;
    options.threads = threads_;
    return options;
  }

  Eigen::Vector3d corner(int f, int k, int v, const Eigen::Vector3d& x) const {
    const int u = mesh_.F(f, k);
    return u == v ? x : Eigen::Vector3d(mesh_.V.row(u).transpose());
  }

  // Whether face f of the unrounded mesh has collinear corners: asked only of faces collinear
  // after rounding (few), so found on demand.
  bool was_collinear(int f) const {
    signed char& known = was_collinear_[static_cast<std::size_t>(f)];
    if (known < 0)
      known = collinear_exact(original_.V.row(original_.F(f, 0)).transpose(), original_.V.row(original_.F(f, 1)).transpose(),
                              original_.V.row(original_.F(f, 2)).transpose())
                  ? 1
                  : 0;
    return known == 1;
  }

  bool collinear(int f, int v, const Eigen::Vector3d& x) const {
    return collinear_exact(corner(f, 0, v, x), corner(f, 1, v, x), corner(f, 2, v, x));
  }

  // New defects among the faces around v with v at x: their collinear faces and their new pairs.
  long long local_defects(int v, const Eigen::Vector3d& x) const {
    const std::size_t begin = first_[static_cast<std::size_t>(v)], end = first_[static_cast<std::size_t>(v) + 1];
    Aabb around;
    long long count = 0;
    for (std::size_t i = begin; i < end; ++i) {
      const int f = incident_[i];
      for (int k = 0; k < 3; ++k) around.extend(corner(f, k, v, x));
      if (collinear(f, v, x) && !was_collinear(f)) ++count;
    }
    around.lo.array() -= slack_;
    around.hi.array() += slack_;
    std::vector<int> near;
    bvh_.traverse([&](const Aabb& box) { return box.overlaps(around); },
                  [&](int g) {
                    near.push_back(g);
                    return near.size() < 4096;  // a cap: a vertex's neighbourhood is small
                  });
    std::sort(near.begin(), near.end());
    for (std::size_t i = begin; i < end; ++i) {
      const int f = incident_[i];
      if (collinear(f, v, x)) continue;
      const Eigen::Vector3d a[3] = {corner(f, 0, v, x), corner(f, 1, v, x), corner(f, 2, v, x)};
      const int ids_f[3] = {mesh_.F(f, 0), mesh_.F(f, 1), mesh_.F(f, 2)};
      for (const int g : near) {
        if (g == f) continue;
        const bool g_incident = mesh_.F(g, 0) == v || mesh_.F(g, 1) == v || mesh_.F(g, 2) == v;
        if (g_incident && g < f) continue;  // counted once, from the smaller face
        if (collinear(g, v, x)) continue;
        const Eigen::Vector3d b[3] = {corner(g, 0, v, x), corner(g, 1, v, x), corner(g, 2, v, x)};
        const int ids_g[3] = {mesh_.F(g, 0), mesh_.F(g, 1), mesh_.F(g, 2)};
        if (!faces_intersect_exact(a, ids_f, b, ids_g)) continue;
        const Pair key{std::min(f, g), std::max(f, g)};
        if (!std::binary_search(reference_.begin(), reference_.end(), key)) ++count;
      }
    }
    return count;
  }

  const Mesh& original_;
  Mesh& mesh_;
  std::vector<char> frozen_;
  std::vector<Pair> reference_;
  std::vector<int> first_, incident_;
  mutable std::vector<signed char> was_collinear_;  // -1 until asked
  double slack_ = 0.0;
  int threads_ = 1;
  TriangleBvh bvh_;
};

Mesh nearest_floats(const Mesh& mesh) {
  Mesh out = mesh;
  for (Eigen::Index i = 0; i < out.V.rows(); ++i)
    for (int c = 0; c < 3; ++c) out.V(i, c) = nearest_float(out.V(i, c));
  return out;
}

// Rounds `mesh` into `rounded` (already at nearest floats) and repairs; returns the defects left,
// and in `found` the pairs of the last search, which was of `rounded` as it is returned (a pass
// that moves nothing ends the repair before another search).
long long repair(const Mesh& mesh, Mesh& rounded, const std::vector<char>& frozen, bool has_reference, int& rounds,
                 IntersectingFaces& found, std::shared_ptr<const TriangleBvh>& tree, int threads) {
  std::vector<Pair> reference;
  Repair probe(mesh, rounded, frozen, {}, threads);
  std::vector<int> faces;
  long long left = probe.new_defects(&faces, found, tree);
  if (left == 0) return 0;
  if (has_reference) {
    BvhOptions options;
    options.threads = threads;
    reference = self_intersections_in_parts(TriangleBvh(mesh.V, mesh.F, options), kPairCap, threads).pairs;
  }
  Repair fix(mesh, rounded, frozen, reference, threads);
  faces.clear();
  left = fix.new_defects(&faces, found, tree);
  for (int round = 0; round < kRoundingRepairRounds && left > 0; ++round) {
    ++rounds;
    if (!fix.pass(faces)) break;
    faces.clear();
    left = fix.new_defects(&faces, found, tree);
  }
  return left;
}

}  // namespace

RoundedForOutput round_for_output(const Mesh& outer, const Mesh& inner, const std::vector<char>& shared,
                                  StoredPrecision precision, int threads) {
  RoundedForOutput out;
  if (precision == StoredPrecision::exact) {
    out.outer = outer;
    out.inner = inner;
    return out;
  }
  out.outer = nearest_floats(outer);
  IntersectingFaces outer_found;
  out.outer_new_pairs = repair(outer, out.outer, {}, true, out.repair_rounds, outer_found, out.outer_tree, threads);
  out.inner = nearest_floats(inner);
  std::vector<char> frozen;
  if (!shared.empty() && inner.V.rows() == outer.V.rows()) {
    frozen = shared;
    for (Eigen::Index i = 0; i < inner.V.rows(); ++i)
      if (shared[static_cast<std::size_t>(i)]) out.inner.V.row(i) = out.outer.V.row(i);
  }
  // New pairs only: pairs the unrounded cavity has already are refused by the verification.
  out.inner_new_pairs = repair(inner, out.inner, frozen, true, out.repair_rounds, out.inner_pairs, out.inner_tree, threads);
  out.inner_searched = true;
  for (const auto* pair : {&outer, &inner}) {
    const Mesh& rounded = pair == &outer ? out.outer : out.inner;
    for (Eigen::Index i = 0; i < pair->V.rows(); ++i)
      for (int c = 0; c < 3; ++c)
        if (rounded.V(i, c) != nearest_float(pair->V(i, c))) {
          ++out.vertices_moved;
          break;
        }
  }
  return out;
}

double rounding_wall_margin(double largest_coordinate, StoredPrecision precision) {
  if (precision == StoredPrecision::exact) return 0.0;
  // Half an ulp of rounding plus kRoundingSearchUlps of repair, per coordinate, for both ends.
  const double per_coordinate = (0.5 + kRoundingSearchUlps) * float_ulp(largest_coordinate);
  return 2.0 * std::sqrt(3.0) * per_coordinate;
}

}  // namespace offsetopt
