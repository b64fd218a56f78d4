#include "cavity/contour_cavity.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "geometry/closest_point.h"
#include "geometry/grid_winding.h"
#include "geometry/marching_tetrahedra.h"
#include "geometry/mesh_shells.h"
#include "util/parallel.h"

namespace offsetopt {

namespace {

constexpr double kMinFraction = 1e-3;  // marching tetrahedra: how close to a node a vertex may sit
constexpr int kBlock = 4;              // nodes per block side in the distance pass
constexpr int kParts = 2;              // every parallel loop is cut into this many fixed parts

Aabb mesh_box(const Mesh& mesh) {
  Aabb box;
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) box.extend(mesh.V.row(i).transpose());
  return box;
}

// The inner term of φ: which nodes lie inside the void it bounds, and a signed distance to its
// boundary (positive inside), capped at ±cap.
class InnerField {
 public:
  virtual ~InnerField() = default;
  virtual Aabb box() const = 0;  // where the void can be
  virtual std::vector<std::int8_t> inside(const NodeGrid& grid, const std::vector<std::int8_t>& outer_winding,
                                          int threads) const = 0;
  virtual double signed_distance(const Eigen::Vector3d& p, bool inside, double cap) const = 0;
};

// The inner offset surface: inside where its winding number is >= 1 (folds and overlaps resolve
// themselves), the distance to its nearest face.
class MeshField final : public InnerField {
 public:
  explicit MeshField(const Mesh& inner) : inner_(inner), bvh_(inner.V, inner.F) {}
  Aabb box() const override { return mesh_box(inner_); }
  std::vector<std::int8_t> inside(const NodeGrid& grid, const std::vector<std::int8_t>&, int threads) const override {
    std::vector<std::int8_t> winding = grid_winding(inner_, grid, threads);
    for (std::int8_t& w : winding) w = w >= 1;
    return winding;
  }
  double signed_distance(const Eigen::Vector3d& p, bool inside, double cap) const override {
    const ClosestPoint to_inner = closest_point(bvh_, p, cap);
    const double d_in = to_inner.found ? to_inner.distance : cap;
    return inside ? d_in : -d_in;
  }

 private:
  const Mesh& inner_;
  TriangleBvh bvh_;
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
  double signed_distance(const Eigen::Vector3d& p, bool inside, double cap) const override {
    const Eigen::Vector3d u = p - centre_;
    const double q = local_value(u);
    const double gradient = local_gradient(u).norm();
    // Where |∇q| vanishes (a centre, an apex) the estimate is unbounded: the cap stands in for it.
    double s = std::fabs(q) >= cap * gradient ? cap : std::fabs(q) / gradient;
    if (!inside) s = -s;
    return s;
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

}  // namespace

std::string ContourCavityOptions::check() const {
  const ContourCavityOptions& o = *this;
  if (!(o.wall > 0.0) || !std::isfinite(o.wall)) return "the wall must be > 0";
  if (!(o.cells_per_wall >= 1.25 && o.cells_per_wall <= 8.0)) return "cells per wall must be in [1.25, 8]";
  if (!(o.margin_cells >= 0.25 && o.margin_cells <= 2.0)) return "the margin must be in [0.25, 2] cells";
  if (o.max_nodes < 1000) return "the node cap must be >= 1000";
  if (!(o.min_shell_fraction >= 0.0 && o.min_shell_fraction < 1.0)) return "the shell fraction must be in [0, 1)";
  if (o.threads < 1 || o.threads > 64) return "threads must be in [1, 64]";
  return "";
}

namespace {

ContourCavity contour_field(const Mesh& outer, const TriangleBvh& outer_bvh, const InnerField& field,
                            const ContourCavityOptions& options) {
  ContourCavity out;
  if (const std::string problem = options.check(); !problem.empty()) {
    out.message = problem;
    return out;
  }
  const double wall = options.wall;
  Aabb box = field.box();
  const Aabb outer_box = mesh_box(outer);
  box.lo = box.lo.cwiseMax(outer_box.lo);
  box.hi = box.hi.cwiseMin(outer_box.hi);
  out.ok = true;
  if (box.empty()) return out;  // no void

  // The spacing: wall / cells_per_wall, coarser when the box would need too many nodes.
  double h = wall / options.cells_per_wall;
  const Eigen::Vector3d extent = box.hi - box.lo;
  auto nodes_for = [&](double spacing) {
    double count = 1.0;
    for (int a = 0; a < 3; ++a) count *= std::ceil(extent(a) / spacing) + 6.0;
    return count;
  };
  for (int grow = 0; grow < 60 && nodes_for(h) > static_cast<double>(options.max_nodes); ++grow) h *= 1.05;
  if (nodes_for(h) > static_cast<double>(options.max_nodes)) {
    out.ok = false;
    out.message = "the cavity grid would need more than " + std::to_string(options.max_nodes) + " nodes";
    return out;
  }
  // The margin: c·h, and never less than what keeps a grid edge (at most √3 h) shorter than
  // wall + margin, or a contoured triangle could reach the outer surface. A grid made coarser by
  // the node cap keeps a thicker wall rather than failing.
  const double margin = std::max(options.margin_cells * h, 1.01 * std::sqrt(3.0) * h - wall);
  NodeGrid& grid = out.grid;
  grid.spacing = h;
  // Offsets by odd fractions of h: grid rows and nodes then miss the round coordinates of CAD
  // meshes (the tie-breaking in grid_winding makes such hits correct anyway, but rarer is cheaper).
  grid.origin = box.lo - Eigen::Vector3d(2.2371, 2.3119, 2.4243) * h;
  grid.nx = static_cast<std::int64_t>(std::ceil(extent.x() / h)) + 6;
  grid.ny = static_cast<std::int64_t>(std::ceil(extent.y() / h)) + 6;
  grid.nz = static_cast<std::int64_t>(std::ceil(extent.z() / h)) + 6;
  const std::int64_t node_count = grid.node_count();

  WorkerPool pool(std::max(1, std::min(options.threads, kParts)));
  // Inside the outer surface and inside the inner one: the candidates for the cavity.
  const std::vector<std::int8_t> outer_winding = grid_winding(outer, grid, options.threads);
  const std::vector<std::int8_t> inner_inside = field.inside(grid, outer_winding, options.threads);
  std::vector<std::int8_t> sign(static_cast<std::size_t>(node_count));  // becomes 1: cavity
  for (std::int64_t v = 0; v < node_count; ++v)
    sign[static_cast<std::size_t>(v)] = outer_winding[static_cast<std::size_t>(v)] >= 1 && inner_inside[static_cast<std::size_t>(v)] != 0;

  // Distance pass: a candidate stays cavity when d_out >= wall + c·h. One query per block of 4³
  // nodes decides most of them by the Lipschitz bound.
  const std::int64_t bx = (grid.nx + kBlock - 1) / kBlock, by = (grid.ny + kBlock - 1) / kBlock,
                     bz = (grid.nz + kBlock - 1) / kBlock;
  const double level = wall + margin;
  const double rounding = 1e-9 * h;  // what a Lipschitz bound gives away to rounding
  std::int64_t per_node[kParts] = {0, 0};
  pool.run_parts(kParts, [&](int part) {
    for (std::int64_t kb = split_point(bz, kParts, part); kb < split_point(bz, kParts, part + 1); ++kb)
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
                if (closest_point(outer_bvh, node, level).found) s = 0;
              }
        }
  });
  out.distance_nodes = per_node[0] + per_node[1];

  // Cells whose nodes disagree, in index order.
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
  out.active_cells = static_cast<std::int64_t>(cells.size());

  // φ at the nodes of those cells. Distances are capped a little beyond where they matter for
  // the interpolation; the sign always comes from the passes above.
  std::vector<std::int64_t> nodes;
  nodes.reserve(cells.size() * 4);
  for (const std::int64_t c : cells)
    for (int corner = 0; corner < 8; ++corner)
      nodes.push_back(c + (corner & 1) + ((corner >> 1) & 1) * grid.nx + ((corner >> 2) & 1) * grid.nx * grid.ny);
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  std::vector<double> phi(nodes.size());
  std::vector<double> outer_distance(nodes.size());  // exact below level + cap, else that cap
  const double cap = 2.0 * h;
  pool.run_parts(kParts, [&](int part) {
    const long count = static_cast<long>(nodes.size());
    for (long n = split_point(count, kParts, part); n < split_point(count, kParts, part + 1); ++n) {
      const std::int64_t node = nodes[static_cast<std::size_t>(n)];
      const Eigen::Vector3d p = grid.position(node);
      const ClosestPoint to_outer = closest_point(outer_bvh, p, level + cap);
      const double d_out = to_outer.found ? to_outer.distance : level + cap;
      outer_distance[static_cast<std::size_t>(n)] = d_out;
      const double signed_out = outer_winding[static_cast<std::size_t>(node)] >= 1 ? d_out : -d_out;
      const double signed_in = field.signed_distance(p, inner_inside[static_cast<std::size_t>(node)] != 0, cap);
      double value = std::min(signed_out - level, signed_in);
      if (sign[static_cast<std::size_t>(node)]) value = std::max(value, 0.0);
      else value = std::min(value, -1e-9 * h);
      phi[static_cast<std::size_t>(n)] = value;
    }
  });
  const auto value_of = [&](std::int64_t node) {
    const auto it = std::lower_bound(nodes.begin(), nodes.end(), node);
    return phi[static_cast<std::size_t>(it - nodes.begin())];
  };
  TetContour contour = marching_tetrahedra(grid, cells, value_of, kMinFraction);

  // The wall, exactly, at every vertex: move it along its edge towards the cavity node.
  int moved[kParts] = {0, 0};
  pool.run_parts(kParts, [&](int part) {
    const long count = static_cast<long>(contour.mesh.V.rows());
    for (long v = split_point(count, kParts, part); v < split_point(count, kParts, part + 1); ++v) {
      const std::int64_t positive = contour.positive_node[static_cast<std::size_t>(v)];
      const Eigen::Vector3d p = grid.position(positive);
      const Eigen::Vector3d q = grid.position(contour.negative_node[static_cast<std::size_t>(v)]);
      double good = kMinFraction, bad = contour.fraction[static_cast<std::size_t>(v)];
      // The cavity node's distance, less the way along the edge, bounds the vertex's: most
      // vertices need no query.
      const double node_distance =
          outer_distance[static_cast<std::size_t>(std::lower_bound(nodes.begin(), nodes.end(), positive) - nodes.begin())];
      if (node_distance - bad * (q - p).norm() >= wall + rounding) continue;
      if (!closest_point(outer_bvh, p + bad * (q - p), wall).found) continue;
      for (int step = 0; step < 40; ++step) {
        const double mid = 0.5 * (good + bad);
        (closest_point(outer_bvh, p + mid * (q - p), wall).found ? bad : good) = mid;
      }
      contour.mesh.V.row(v) = (p + good * (q - p)).transpose();
      ++moved[part];
    }
  });
  out.vertices_moved_for_wall = moved[0] + moved[1];

  // Shells: keep those that enclose void of some size.
  const MeshShells shells = mesh_shells(contour.mesh, grid.origin);
  const std::vector<int>& shell = shells.shell_of_face;
  double total = 0.0;
  for (double v : shells.volume) total += std::max(v, 0.0);
  std::vector<char> keep(shells.volume.size(), 0);
  for (std::size_t s = 0; s < shells.volume.size(); ++s) {
    const double volume = shells.volume[s];
    keep[s] = volume > options.min_shell_fraction * total && volume > 0.0;
    if (keep[s]) ++out.shells;
    else {
      ++out.shells_dropped;
      out.dropped_volume += volume;
    }
  }
  std::vector<int> new_index(static_cast<std::size_t>(contour.mesh.V.rows()), -1);
  int vertex_count = 0, face_count = 0;
  for (Eigen::Index f = 0; f < contour.mesh.F.rows(); ++f) {
    if (!keep[static_cast<std::size_t>(shell[static_cast<std::size_t>(f)])]) continue;
    ++face_count;
    for (int c = 0; c < 3; ++c) {
      int& index = new_index[static_cast<std::size_t>(contour.mesh.F(f, c))];
      if (index < 0) index = vertex_count++;
    }
  }
  out.cavity.V.resize(vertex_count, 3);
  out.cavity.F.resize(face_count, 3);
  for (Eigen::Index v = 0; v < contour.mesh.V.rows(); ++v)
    if (new_index[static_cast<std::size_t>(v)] >= 0) out.cavity.V.row(new_index[static_cast<std::size_t>(v)]) = contour.mesh.V.row(v);
  int row = 0;
  for (Eigen::Index f = 0; f < contour.mesh.F.rows(); ++f) {
    if (!keep[static_cast<std::size_t>(shell[static_cast<std::size_t>(f)])]) continue;
    for (int c = 0; c < 3; ++c) out.cavity.F(row, c) = new_index[static_cast<std::size_t>(contour.mesh.F(f, c))];
    ++row;
  }
  return out;
}

}  // namespace

ContourCavity contour_cavity(const Mesh& outer, const TriangleBvh& outer_bvh, const Mesh& inner,
                             const ContourCavityOptions& options) {
  if (inner.F.rows() == 0) {  // no void
    ContourCavity out;
    out.message = options.check();
    out.ok = out.message.empty();
    return out;
  }
  return contour_field(outer, outer_bvh, MeshField(inner), options);
}

ContourCavity contour_cavity(const Mesh& outer, const TriangleBvh& outer_bvh, const Vector10d& quadric,
                             const ContourCavityOptions& options) {
  if (!quadric.allFinite()) {
    ContourCavity out;
    out.message = "the quadric's coefficients must be finite";
    return out;
  }
  return contour_field(outer, outer_bvh, QuadricField(quadric, mesh_box(outer)), options);
}

}  // namespace offsetopt
