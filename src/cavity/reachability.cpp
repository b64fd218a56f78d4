#include "cavity/reachability.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "cavity/contour_cavity.h"
#include "cavity/wall_deep_shares.h"
#include "geometry/aabb.h"
#include "mass/volume_integrals.h"
#include "optim/transposed_product_10.h"
#include "util/neumaier_sum.h"

namespace offsetopt {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Vector10d unit(int k) {
  Vector10d e = Vector10d::Zero();
  e(k) = 1.0;
  return e;
}

// An affine function of the occupancy: constant + solid·S + hollow·Q, S the solid's integrals and Q
// the void's (normalised frame). A void cell moves its integrals from S to Q, a band cell adds them
// to S.
struct Form {
  Vector10d solid = Vector10d::Zero(), hollow = Vector10d::Zero();
  double constant = 0.0;
  Vector10d void_coefficients() const { return hollow - solid; }
};

Form solid_form(const Vector10d& g, double constant = 0.0) {
  Form f;
  f.solid = g;
  f.constant = constant;
  return f;
}

Form minus(const Form& a, double t, const Form& b) {
  Form f;
  f.solid = a.solid - t * b.solid;
  f.hollow = a.hollow - t * b.hollow;
  f.constant = a.constant - t * b.constant;
  return f;
}

struct GoalRows {
  std::vector<Form> numerators, denominators;  // ratio rows N_j >= t D_j (D_j > 0)
  std::vector<std::string> ratio_names;
  std::vector<Form> plain;                     // rows F >= 0
  std::vector<std::string> plain_names;
};

// The goal's rows in the normalised frame (x̃ = s (R p − o)). `tau` is the axis tolerance
// (fraction of the diagonal), `volume_tau` and `inertia_tau` the float and spin ones; `level` the
// spin's height c (negative: no "Izz largest" rows).
struct Frame {
  double scale = 1.0;                 // 1 / diagonal
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // o, rotated input units
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Vector10d P0 = Vector10d::Zero();   // the input's integrals, normalised frame
  double top = 1.0;                   // highest point over the ground, normalised
  // The corners of a box holding every solid the cells describe (the grid's: the input's box,
  // grown by outer_max with the band), normalised.
  std::array<Eigen::Vector3d, 8> region;
  Eigen::Vector3d to_frame(const Eigen::Vector3d& posed) const { return (posed - origin) * scale; }
};

void add_axis_rows(GoalRows& rows, double x0, double y0, double tau, const std::string& what) {
  const Vector10d e0 = unit(kIntVolume);
  const Vector10d gx = unit(kIntX) - x0 * e0, gy = unit(kIntY) - y0 * e0;
  rows.plain.push_back(solid_form(tau * e0 - gx));
  rows.plain.push_back(solid_form(tau * e0 + gx));
  rows.plain.push_back(solid_form(tau * e0 - gy));
  rows.plain.push_back(solid_form(tau * e0 + gy));
  rows.plain_names.insert(rows.plain_names.end(), {what + " x", what + " x", what + " y", what + " y"});
}

GoalRows goal_rows(const GoalSpec& goal, const Frame& f, double tau, double volume_tau, double inertia_tau, double level) {
  GoalRows rows;
  const Vector10d e0 = unit(kIntVolume);
  const double V0 = f.P0(kIntVolume);
  switch (goal.kind) {
    case GoalKind::stand:
    case GoalKind::stand_filled: {
      const std::size_t n = goal.support_polygon.size();
      for (int filled = 0; filled < (goal.kind == GoalKind::stand_filled ? 2 : 1); ++filled)
        for (std::size_t e = 0; e < n; ++e) {
          const Eigen::Vector3d a3 = f.to_frame(Eigen::Vector3d(goal.support_polygon[e].x(), goal.support_polygon[e].y(), 0.0));
          const Eigen::Vector3d b3 =
              f.to_frame(Eigen::Vector3d(goal.support_polygon[(e + 1) % n].x(), goal.support_polygon[(e + 1) % n].y(), 0.0));
          const Eigen::Vector2d a = a3.head<2>(), edge = b3.head<2>() - a;
          const Eigen::Vector2d inward = Eigen::Vector2d(-edge.y(), edge.x()) / edge.norm();
          const Vector10d g = -inward.dot(a) * e0 + inward.x() * unit(kIntX) + inward.y() * unit(kIntY);
          Form N = solid_form(g), D = solid_form(e0);
          if (filled) {
            N.hollow = goal.fill_density * g;
            D.hollow = goal.fill_density * e0;
          }
          rows.numerators.push_back(N);
          rows.denominators.push_back(D);
          rows.ratio_names.push_back(std::string(filled ? "filled, support edge " : "support edge ") + std::to_string(e));
        }
      break;
    }
    case GoalKind::roly_poly: {
      const Eigen::Vector3d c = f.to_frame(goal.axis_point);
      add_axis_rows(rows, c.x(), c.y(), tau, "sphere axis");
      rows.numerators.push_back(solid_form(c.z() * e0 - unit(kIntZ)));
      rows.denominators.push_back(solid_form(e0));
      rows.ratio_names.push_back("height below the sphere centre");
      break;
    }
    case GoalKind::floating: {
      const double rho = goal.fluid_density;
      rows.plain.push_back(solid_form((volume_tau + 1.0) * e0, -rho * V0));
      rows.plain.push_back(solid_form((volume_tau - 1.0) * e0, rho * V0));
      rows.plain_names.insert(rows.plain_names.end(), {"buoyancy equals weight", "buoyancy equals weight"});
      const Eigen::Vector3d cb = f.P0.segment<3>(kIntX) / V0;
      add_axis_rows(rows, cb.x(), cb.y(), tau, "buoyancy axis");
      rows.numerators.push_back(solid_form(cb.z() * e0 - unit(kIntZ)));
      rows.denominators.push_back(solid_form(e0));
      rows.ratio_names.push_back("depth below the centre of buoyancy");
      break;
    }
    case GoalKind::spin: {
      const Eigen::Vector3d tip = f.to_frame(goal.axis_point);
      const double x0 = tip.x(), y0 = tip.y();
      add_axis_rows(rows, x0, y0, tau, "spin axis");
      const Vector10d xx = unit(kIntXX) - 2.0 * x0 * unit(kIntX) + x0 * x0 * e0;
      const Vector10d yy = unit(kIntYY) - 2.0 * y0 * unit(kIntY) + y0 * y0 * e0;
      const Vector10d xy = unit(kIntXY) - x0 * unit(kIntY) - y0 * unit(kIntX) + x0 * y0 * e0;
      const Vector10d J = xx + yy;
      for (const Vector10d& p : {Vector10d(unit(kIntZX) - x0 * unit(kIntZ)), Vector10d(unit(kIntYZ) - y0 * unit(kIntZ))}) {
        rows.plain.push_back(solid_form(inertia_tau * J - p));
        rows.plain.push_back(solid_form(inertia_tau * J + p));
        rows.plain_names.insert(rows.plain_names.end(), {"inertia product", "inertia product"});
      }
      if (level >= 0.0) {
        const Vector10d zz = unit(kIntZZ) - 2.0 * level * unit(kIntZ) + level * level * e0;
        // Directions ((1 − t²), 2t) / (1 + t²) for t in [−1, 1]: half the circle, enough (±e).
        const int k = 24;
        for (int i = 0; i < k; ++i) {
          const double t = -1.0 + 2.0 * i / k;
          const double ax = (1.0 - t * t) / (1.0 + t * t), ay = 2.0 * t / (1.0 + t * t);
          rows.plain.push_back(solid_form(ax * ax * xx + 2.0 * ax * ay * xy + ay * ay * yy - zz));
          rows.plain_names.push_back("z the largest moment");
        }
      }
      break;
    }
    case GoalKind::volume: break;
  }
  return rows;
}

// The fine cells of one reading, in the normalised frame, grouped into LP columns.
struct FineCell {
  Eigen::Vector3d x;     // centre, normalised frame
  std::int32_t i = 0, j = 0, k = 0;  // grid indices (for the block hierarchy)
  std::int8_t sign = -1; // −1 void, +1 band (material added), −2 skin (material shaved, --outer)
  int source = 0;        // index in its CarvableCells list
  double share = 1.0;    // of the cube a void may hold (cavity/wall_deep_shares.h); 1 but on the generous reading's shell
};

struct Group {
  int begin = 0, end = 0;          // into Partition::order
  int side = 1;                    // block side in cells (a power of two times 1)
  Vector10d integrals = Vector10d::Zero();
  std::int8_t sign = -1;
};

struct Partition {
  std::vector<FineCell> cells;
  std::vector<int> order;          // cells, block by block
  std::vector<Group> groups;
  int splits = 0;                  // times the groups were replaced (Solver::moved_at's key)
  double h = 0.0;                  // cell side, normalised
  // cube_integrals(centre, h, 0), the same arithmetic inlined: the block splits evaluate it for
  // every cell of every block they look at.
  Vector10d cell_integrals(int c) const {
    const FineCell& cell = cells[static_cast<std::size_t>(c)];
    const Eigen::Vector3d& x = cell.x;
    const double v = h * h * h * cell.share, s = h * h / 12.0;
    Vector10d out;
    out << v, v * x.x(), v * x.y(), v * x.z(), v * (x.x() * x.x() + s), v * (x.y() * x.y() + s), v * (x.z() * x.z() + s),
        v * x.x() * x.y(), v * x.y() * x.z(), v * x.z() * x.x();
    return out;
  }
};

// `void_shares`, when given, per `voids`: the share of each void cell's cube a void may hold, its
// column the cube's integrals times it (the void's part of a cube is not the cube's moments
// scaled, but the programme only proposes; the certificate bounds every cube rigorously).
Partition make_partition(const CarvableCells& cc, const std::vector<std::int64_t>& voids, const std::vector<std::int64_t>& band,
                         const std::vector<std::int64_t>& skin, const Frame& f, int block,
                         const std::vector<double>* void_shares = nullptr) {
  Partition p;
  p.h = cc.grid.spacing * f.scale;
  const NodeGrid& g = cc.grid;
  const std::int64_t bx = (g.nx + block - 1) / block, by = (g.ny + block - 1) / block, bz = (g.nz + block - 1) / block;
  std::vector<std::int64_t> key;
  const std::size_t total = voids.size() + band.size() + skin.size();
  p.cells.reserve(total);
  key.reserve(total);
  for (int sign : {-1, 1, -2}) {
    const std::vector<std::int64_t>& list = sign == -1 ? voids : sign == 1 ? band : skin;
    const int kind = sign == -1 ? 0 : sign == 1 ? 1 : 2;
    for (std::size_t s = 0; s < list.size(); ++s) {
      const double share = sign == -1 && void_shares ? (*void_shares)[s] : 1.0;
      if (share == 0.0) continue;  // no point of it a wall deep
      const std::int64_t cell = list[s];
      const std::int64_t i = cell % g.nx, j = (cell / g.nx) % g.ny, k = cell / (g.nx * g.ny);
      FineCell fc;
      fc.x = f.to_frame(f.rotation * cc.centre(i, j, k));
      fc.i = static_cast<std::int32_t>(i);
      fc.j = static_cast<std::int32_t>(j);
      fc.k = static_cast<std::int32_t>(k);
      fc.sign = static_cast<std::int8_t>(sign);
      fc.source = static_cast<int>(s);
      fc.share = share;
      p.cells.push_back(fc);
      key.push_back((kind * bz + k / block) * bx * by + (j / block) * bx + i / block);
    }
  }
  // Counting sort by block (stable: cells keep their order inside a block).
  const std::int64_t blocks = 3 * bx * by * bz;
  std::vector<int> start(static_cast<std::size_t>(blocks) + 1, 0);
  for (std::int64_t k : key) ++start[static_cast<std::size_t>(k) + 1];
  for (std::int64_t b = 0; b < blocks; ++b) start[static_cast<std::size_t>(b) + 1] += start[static_cast<std::size_t>(b)];
  p.order.resize(p.cells.size());
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (std::size_t c = 0; c < key.size(); ++c) p.order[static_cast<std::size_t>(fill[static_cast<std::size_t>(key[c])]++)] = static_cast<int>(c);
  for (std::int64_t b = 0; b < blocks; ++b) {
    const int s = start[static_cast<std::size_t>(b)], e = start[static_cast<std::size_t>(b) + 1];
    if (s == e) continue;
    Group grp;
    grp.begin = s;
    grp.end = e;
    grp.sign = p.cells[static_cast<std::size_t>(p.order[static_cast<std::size_t>(s)])].sign;
    grp.side = block;
    for (int q = s; q < e; ++q) grp.integrals += p.cell_integrals(p.order[static_cast<std::size_t>(q)]);
    p.groups.push_back(grp);
  }
  return p;
}

// Coefficient of a form on a column of integrals I with sign s.
double form_on(const Form& f, const Vector10d& I, int sign) {
  return sign == -1 ? f.void_coefficients().dot(I) : sign == 1 ? f.solid.dot(I) : -f.solid.dot(I);
}

// The integrals an occupancy moves: carved out (void cells), added (band), shaved (skin), each
// summed once over the groups, so that every row is then a 10-term dot product (a row per group
// and row cost 10³× more on a round base with hundreds of edges).
struct Moved {
  Vector10d carved = Vector10d::Zero(), added = Vector10d::Zero(), shaved = Vector10d::Zero();
};

Moved moved_integrals(const Partition& p, const std::vector<double>& u) {
  NeumaierSum sums[3][10];
  for (std::size_t g = 0; g < p.groups.size(); ++g) {
    if (u[g] == 0.0) continue;
    const Group& grp = p.groups[g];
    NeumaierSum* to = sums[grp.sign == -1 ? 0 : grp.sign == 1 ? 1 : 2];
    for (int k = 0; k < 10; ++k) to[k].add(u[g] * grp.integrals(k));
  }
  Moved m;
  for (int k = 0; k < 10; ++k) {
    m.carved(k) = sums[0][k].value();
    m.added(k) = sums[1][k].value();
    m.shaved(k) = sums[2][k].value();
  }
  return m;
}

double form_value(const Form& f, const Vector10d& P0, const Moved& m) {
  NeumaierSum sum;
  sum.add(f.constant);
  sum.add(f.solid.dot(P0));
  sum.add(f.void_coefficients().dot(m.carved));
  sum.add(f.solid.dot(m.added));
  sum.add(-f.solid.dot(m.shaved));
  return sum.value();
}

struct LpRun {
  LpStatus status = LpStatus::numerical;
  std::vector<double> u;           // per group
  double z = 0.0;
  std::vector<Form> rows;          // the rows as solved (each >= 0, ratio rows minus z)
  int ratio_rows = 0;
  Eigen::VectorXd weights;         // w >= 0 per row (from the duals or the Farkas certificate)
  // A void cell's reduced cost is void_reduced · (its integrals), normalised frame: positive where
  // the optimum carves (optimal runs only).
  Vector10d void_reduced = Vector10d::Zero();
};

class Solver {
 public:
  Solver(const Frame& f, const ReachabilityOptions& o, Reachability& out) : f_(f), o_(o), out_(out) {}

  // max z (with_z) or max objective, s.t. rows (ratio rows minus z when with_z) >= 0, over the
  // partition, splitting blocks until the duals agree with every cell. `warm` per group.
  // Row generation over solve_rows: most rows (a round base has dozens of support edges) never
  // bind, so the LP starts with the rows lowest at the warm start and adds the most violated ones
  // until the solution meets every row. A subset that is infeasible proves the whole set is.
  LpRun solve(Partition& p, const std::vector<Form>& rows, int ratio_rows, bool with_z, const Form* objective,
              std::vector<double>& warm) {
    const int m = static_cast<int>(rows.size());
    const double V0 = f_.P0(kIntVolume);
    std::vector<char> active(static_cast<std::size_t>(m), 0);
    auto values_at = [&](const std::vector<double>& u) {
      std::vector<double> v(static_cast<std::size_t>(m));
      const Moved& moved = moved_at(p, u);
      for (int k = 0; k < m; ++k) v[static_cast<std::size_t>(k)] = form_value(rows[static_cast<std::size_t>(k)], f_.P0, moved) / V0;
      return v;
    };
    auto add_lowest = [&](const std::vector<double>& v, double z, int count, double below) {
      std::vector<std::pair<double, int>> order;
      for (int k = 0; k < m; ++k)
        if (!active[static_cast<std::size_t>(k)]) order.emplace_back(v[static_cast<std::size_t>(k)] - (k < ratio_rows ? z : 0.0), k);
      std::sort(order.begin(), order.end());
      int added = 0;
      for (const auto& [value, k] : order) {
        if (added == count || value >= below) break;
        active[static_cast<std::size_t>(k)] = 1;
        ++added;
      }
      return added;
    };
    if (warm.size() != p.groups.size()) warm.assign(p.groups.size(), 0.0);
    for (int k = ratio_rows; k < m; ++k) active[static_cast<std::size_t>(k)] = 1;  // few, and often equalities
    add_lowest(values_at(warm), 0.0, 6, kInf);
    // The rows the last programme on this partition ended with (a Dinkelbach step moves t, not
    // which rows bind): its basis names them, and re-adding them one violation at a time costs
    // a dual pass each.
    if (active_partition_ == &p && last_active_.size() == active.size())
      for (std::size_t k = 0; k < active.size(); ++k) active[k] = active[k] || last_active_[k];
    auto keep_active = [&] {
      active_partition_ = &p;
      last_active_ = active;
    };
    for (int pass = 0;; ++pass) {
      std::vector<int> index;
      for (int k = 0; k < m; ++k)
        if (active[static_cast<std::size_t>(k)] && k < ratio_rows) index.push_back(k);
      const int active_ratio = static_cast<int>(index.size());
      for (int k = ratio_rows; k < m; ++k)
        if (active[static_cast<std::size_t>(k)]) index.push_back(k);
      std::vector<Form> subset;
      for (int k : index) subset.push_back(rows[static_cast<std::size_t>(k)]);
      LpRun run = solve_rows(p, subset, index, active_ratio, with_z, objective, warm);
      // Back to every row: the inactive ones weigh nothing.
      Eigen::VectorXd weights = Eigen::VectorXd::Zero(m);
      for (std::size_t i = 0; i < index.size() && static_cast<Eigen::Index>(i) < run.weights.size(); ++i)
        weights(index[i]) = run.weights(static_cast<Eigen::Index>(i));
      run.weights = weights;
      run.rows = rows;
      run.ratio_rows = ratio_rows;
      keep_active();
      if (run.status != LpStatus::optimal || pass >= 100) return run;
      if (add_lowest(values_at(run.u), with_z && active_ratio > 0 ? run.z : 0.0, 8, -1e-12) == 0) return run;
    }
  }

  // Drops what the solver keeps per partition (keyed by its address): for a partition built
  // where a discarded one lived.
  void forget_partitions() { moved_partition_ = basis_partition_ = active_partition_ = nullptr; }

  // moved_integrals(p, u), kept for the last (partition, its splits, u) asked: a programme's
  // caller reads its rows at the same occupancy the row generation last did, and the next
  // programme starts from it.
  const Moved& moved_at(const Partition& p, const std::vector<double>& u) {
    if (!(moved_partition_ == &p && moved_splits_ == p.splits && moved_groups_ == p.groups.size() && moved_u_ == u)) {
      moved_ = moved_integrals(p, u);
      moved_partition_ = &p;
      moved_splits_ = p.splits;
      moved_groups_ = p.groups.size();
      moved_u_ = u;
    }
    return moved_;
  }

  // `row_ids` names each row in the caller's full list (rows keep their names across Dinkelbach
  // steps and row generation), so that the last optimal basis can start the next programme.
  LpRun solve_rows(Partition& p, const std::vector<Form>& rows, const std::vector<int>& row_ids, int ratio_rows, bool with_z,
                   const Form* objective, std::vector<double>& warm) {
    LpRun run;
    run.rows = rows;
    run.ratio_rows = ratio_rows;
    const double V0 = f_.P0(kIntVolume);
    const int m = static_cast<int>(rows.size());
    // The last round's columns and costs, and for each group the one it was there (−1: split
    // since): a block split leaves most groups, and so their columns, as they were.
    Eigen::MatrixXd kept_A;
    Eigen::VectorXd kept_c;
    std::vector<int> kept_from;
    for (int round = 0;; ++round) {
      const int G = static_cast<int>(p.groups.size());
      LinearProgram lp;
      lp.A.resize(m, G + (with_z ? 1 : 0));
      lp.b.resize(m);
      lp.sense.assign(static_cast<std::size_t>(m), RowSense::greater_equal);
      lp.c = Eigen::VectorXd::Zero(lp.A.cols());
      lp.lower = Eigen::VectorXd::Zero(lp.A.cols());
      lp.upper = Eigen::VectorXd::Ones(lp.A.cols());
      Eigen::Matrix<double, 10, Eigen::Dynamic> cv(10, m), cb(10, m);
      for (int k = 0; k < m; ++k) {
        cv.col(k) = rows[static_cast<std::size_t>(k)].void_coefficients() / V0;
        cb.col(k) = rows[static_cast<std::size_t>(k)].solid / V0;
        lp.b(k) = -(rows[static_cast<std::size_t>(k)].constant + rows[static_cast<std::size_t>(k)].solid.dot(f_.P0)) / V0;
      }
      for (int g = 0; g < G; ++g) {
        if (!kept_from.empty() && kept_from[static_cast<std::size_t>(g)] >= 0) {
          const int was = kept_from[static_cast<std::size_t>(g)];
          lp.A.col(g) = kept_A.col(was);
          if (objective) lp.c(g) = kept_c(was);
          continue;
        }
        const Group& grp = p.groups[static_cast<std::size_t>(g)];
        const Eigen::Matrix<double, 10, Eigen::Dynamic>& coefficients = grp.sign == -1 ? cv : cb;
        if (m == 1) {
          lp.A.col(g).noalias() = coefficients.transpose() * grp.integrals;
        } else {
          transposed_product_10(coefficients, grp.integrals, lp.A.col(g).data());  // the product's bits
        }
        if (grp.sign == -2) lp.A.col(g) = -lp.A.col(g);
        if (objective) lp.c(g) = form_on(*objective, grp.integrals, grp.sign) / V0;
      }
      if (with_z) {
        lp.A.col(G).setZero();
        lp.A.col(G).head(ratio_rows).setConstant(-1.0);
        lp.c(G) = 1.0;
        lp.lower(G) = -kInf;
        lp.upper(G) = kInf;
      }
      std::vector<std::int8_t> start(static_cast<std::size_t>(lp.A.cols()), 0);
      for (int g = 0; g < G; ++g) start[static_cast<std::size_t>(g)] = warm[static_cast<std::size_t>(g)] > 0.5;
      const std::vector<int> start_basis = basis_for(p, row_ids, with_z);
      const LpResult r = bounded_simplex(lp, o_.lp, &start, start_basis.empty() ? nullptr : &start_basis);
      keep_basis(p, row_ids, r);
      ++out_.lps;
      out_.lp_iterations += r.iterations;
      out_.pricing_passes += r.pricing_passes;
      out_.columns = static_cast<int>(lp.A.cols());
      run.status = r.status;
      run.weights = (-r.y).cwiseMax(0.0);
      if (r.status != LpStatus::optimal) {
        if (r.status == LpStatus::infeasible) run.u.assign(static_cast<std::size_t>(G), 0.0);
        return run;
      }
      run.u.assign(static_cast<std::size_t>(G), 0.0);
      for (int g = 0; g < G; ++g) run.u[static_cast<std::size_t>(g)] = std::min(1.0, std::max(0.0, r.x(g)));
      run.z = with_z ? r.x(G) : 0.0;
      // Reduced cost of a cell: objective − yᵀ column, a 10-vector dotted with its integrals.
      Vector10d wv = cv * r.y, wb = cb * r.y;
      wv = -wv;
      wb = -wb;
      if (objective) {
        wv += objective->void_coefficients() / V0;
        wb += objective->solid / V0;
      }
      run.void_reduced = wv;
      const Vector10d ws = -wb;  // a shaved cell is an added one with the opposite sign
      auto weights_of = [&](int sign) -> const Vector10d& { return sign == -1 ? wv : sign == 1 ? wb : ws; };
      const double tol = o_.lp.optimality_tolerance;
      std::vector<char> split(static_cast<std::size_t>(G), 0);
      bool any = false;
      for (int g = 0; g < G; ++g) {
        const Group& grp = p.groups[static_cast<std::size_t>(g)];
        if (grp.end - grp.begin == 1) continue;
        const double u = run.u[static_cast<std::size_t>(g)];
        bool bad = false;
        const Vector10d& w = weights_of(grp.sign);
        // A block whose reduced costs all keep the sign its bound asks for, by a bound over the
        // block's ball, is left whole without visiting its cells (most blocks, away from {q = 0}).
        if (u >= 1.0 - 1e-9 || u <= 1e-9) {
          const auto [low, high] = block_reduced_costs(p, grp, w);
          if (u >= 1.0 - 1e-9 ? low >= -tol : high <= tol) continue;
        }
        for (int q = grp.begin; q < grp.end && !bad; ++q) {
          const double d = w.dot(p.cell_integrals(p.order[static_cast<std::size_t>(q)]));
          bad = u >= 1.0 - 1e-9 ? d < -tol : u <= 1e-9 ? d > tol : std::fabs(d) > tol;
        }
        split[static_cast<std::size_t>(g)] = bad;
        any = any || bad;
      }
      if (!any || round >= o_.max_refinements) {
        warm = run.u;
        return run;
      }
      std::vector<Group> groups;
      std::vector<double> next_warm;
      std::vector<int> from;
      std::vector<int> octants, sorted;
      for (int g = 0; g < G; ++g) {
        const Group& grp = p.groups[static_cast<std::size_t>(g)];
        if (!split[static_cast<std::size_t>(g)]) {
          groups.push_back(grp);
          next_warm.push_back(run.u[static_cast<std::size_t>(g)]);
          from.push_back(g);
          continue;
        }
        // Into its (up to) 8 octants, cells kept in order inside each.
        const Vector10d& w = weights_of(grp.sign);
        const int half = std::max(1, grp.side / 2);
        // Each cell's octant once, then a stable counting sort by it.
        const int count = grp.end - grp.begin;
        octants.resize(static_cast<std::size_t>(count));
        int first[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
        for (int q = 0; q < count; ++q) {
          const FineCell& c = p.cells[static_cast<std::size_t>(p.order[static_cast<std::size_t>(grp.begin + q)])];
          const int o = (c.i / half) % 2 + 2 * ((c.j / half) % 2) + 4 * ((c.k / half) % 2);
          octants[static_cast<std::size_t>(q)] = o;
          ++first[o + 1];
        }
        for (int o = 0; o < 8; ++o) first[o + 1] += first[o];
        sorted.resize(static_cast<std::size_t>(count));
        int next[8];
        std::copy(first, first + 8, next);
        for (int q = 0; q < count; ++q)
          sorted[static_cast<std::size_t>(next[octants[static_cast<std::size_t>(q)]]++)] = p.order[static_cast<std::size_t>(grp.begin + q)];
        std::copy(sorted.begin(), sorted.end(), p.order.begin() + grp.begin);
        for (int o = 0; o < 8; ++o) {
          if (first[o] == first[o + 1]) continue;
          Group child;
          child.begin = grp.begin + first[o];
          child.sign = grp.sign;
          child.side = half;
          for (int q = child.begin; q < grp.begin + first[o + 1]; ++q) child.integrals += p.cell_integrals(p.order[static_cast<std::size_t>(q)]);
          child.end = grp.begin + first[o + 1];
          groups.push_back(child);
          next_warm.push_back(w.dot(child.integrals) > 0.0 ? 1.0 : 0.0);
          from.push_back(-1);
        }
      }
      p.groups = std::move(groups);
      ++p.splits;
      kept_A = std::move(lp.A);
      kept_c = std::move(lp.c);
      kept_from = std::move(from);
      warm = std::move(next_warm);
    }
  }

  // Bounds of w · (a cell's integrals) over the cells of a block (all lie in the ball around the
  // block's cube centre that reaches its corner cells' centres), widened by far more than the
  // rounding of the cells' own evaluation: with v the cell volume and s = h²/12, a cell's value
  // is v (q(x) + s (w₄ + w₅ + w₆)) with q = w · m(x), and q within the ball is bounded by its value,
  // gradient and Hessian at the centre.
  std::pair<double, double> block_reduced_costs(const Partition& p, const Group& grp, const Vector10d& w) const {
    const FineCell& any = p.cells[static_cast<std::size_t>(p.order[static_cast<std::size_t>(grp.begin)])];
    const int side = grp.side;
    const Eigen::Vector3d index_offset((any.i / side) * side + 0.5 * (side - 1) - any.i,
                                       (any.j / side) * side + 0.5 * (side - 1) - any.j,
                                       (any.k / side) * side + 0.5 * (side - 1) - any.k);
    const Eigen::Vector3d x = any.x + p.h * (f_.rotation * index_offset);
    const double rho = 0.5 * std::sqrt(3.0) * (side - 1) * p.h;
    const double v = p.h * p.h * p.h, s = p.h * p.h / 12.0;
    const double terms[10] = {w(0), w(1) * x.x(), w(2) * x.y(), w(3) * x.z(), w(4) * x.x() * x.x(), w(5) * x.y() * x.y(),
                              w(6) * x.z() * x.z(), w(7) * x.x() * x.y(), w(8) * x.y() * x.z(), w(9) * x.z() * x.x()};
    double q = 0.0, magnitude = 0.0;
    for (const double t : terms) {
      q += t;
      magnitude += std::fabs(t);
    }
    const Eigen::Vector3d grad(w(1) + 2.0 * w(4) * x.x() + w(7) * x.y() + w(9) * x.z(),
                               w(2) + 2.0 * w(5) * x.y() + w(7) * x.x() + w(8) * x.z(),
                               w(3) + 2.0 * w(6) * x.z() + w(8) * x.y() + w(9) * x.x());
    const double hessian = 2.0 * std::sqrt(w(4) * w(4) + w(5) * w(5) + w(6) * w(6)) +
                           std::sqrt(2.0 * (w(7) * w(7) + w(8) * w(8) + w(9) * w(9)));  // ≥ its spectral norm
    const double shift = s * (w(4) + w(5) + w(6));
    const double spread = grad.norm() * rho + 0.5 * hessian * rho * rho;
    const double slack = 1e-9 * (magnitude + spread + std::fabs(shift)) + 1e-300;
    return {v * (q + shift - spread - slack), v * (q + shift + spread + slack)};
  }

  // The last optimal basis by name: a group of cells by its range in the partition's order (a
  // group left whole keeps it through block splits), a slack by its row's name, and the margin
  // column. Kept per partition.
  struct BasisEntry {
    int kind = 0;  // 0 group, 1 slack, 2 the margin column z
    int a = 0, b = 0;
  };
  const Partition* moved_partition_ = nullptr;
  int moved_splits_ = 0;
  std::size_t moved_groups_ = 0;
  std::vector<double> moved_u_;
  Moved moved_;
  const Partition* basis_partition_ = nullptr;
  const Partition* active_partition_ = nullptr;
  std::vector<char> last_active_;
  std::vector<BasisEntry> basis_;

  void keep_basis(const Partition& p, const std::vector<int>& row_ids, const LpResult& r) {
    basis_.clear();
    basis_partition_ = nullptr;
    if (r.status != LpStatus::optimal) return;
    const int G = static_cast<int>(p.groups.size()), n = static_cast<int>(r.x.size());
    for (int var : r.basis) {
      BasisEntry e;
      if (var < G) {
        e.a = p.groups[static_cast<std::size_t>(var)].begin;
        e.b = p.groups[static_cast<std::size_t>(var)].end;
      } else if (var < n) {
        e.kind = 2;
      } else {
        e.kind = 1;
        e.a = row_ids[static_cast<std::size_t>(var - n)];
      }
      basis_.push_back(e);
    }
    basis_partition_ = &p;
  }

  // The kept basis in this programme's numbering, completed by slacks of the rows it does not
  // name; empty when there is none (or it names more than the rows).
  std::vector<int> basis_for(const Partition& p, const std::vector<int>& row_ids, bool with_z) const {
    std::vector<int> out;
    if (basis_partition_ != &p || basis_.empty()) return out;
    const int G = static_cast<int>(p.groups.size()), m = static_cast<int>(row_ids.size());
    const int n = G + (with_z ? 1 : 0);
    std::vector<char> used(static_cast<std::size_t>(n + m), 0);
    auto take = [&](int var) {
      if (var < 0 || used[static_cast<std::size_t>(var)]) return;
      used[static_cast<std::size_t>(var)] = 1;
      out.push_back(var);
    };
    for (const BasisEntry& e : basis_) {
      if (e.kind == 2) {
        if (with_z) take(G);
      } else if (e.kind == 1) {
        const auto it = std::find(row_ids.begin(), row_ids.end(), e.a);
        if (it != row_ids.end()) take(n + static_cast<int>(it - row_ids.begin()));
      } else {
        // Groups are in increasing `begin` (splits replace a group by its octants in place).
        const auto it = std::lower_bound(p.groups.begin(), p.groups.end(), e.a,
                                         [](const Group& g, int begin) { return g.begin < begin; });
        if (it != p.groups.end() && it->begin == e.a && it->end == e.b) take(static_cast<int>(it - p.groups.begin()));
      }
    }
    for (int i = 0; i < m && static_cast<int>(out.size()) < m; ++i) take(n + i);
    if (static_cast<int>(out.size()) != m) out.clear();
    return out;
  }

  const Frame& f_;
  const ReachabilityOptions& o_;
  Reachability& out_;
};

std::vector<Form> ratio_rows_at(const GoalRows& rows, double t) {
  std::vector<Form> out;
  for (std::size_t j = 0; j < rows.numerators.size(); ++j) out.push_back(minus(rows.numerators[j], t, rows.denominators[j]));
  out.insert(out.end(), rows.plain.begin(), rows.plain.end());
  return out;
}

struct MarginSearch {
  bool feasible = false;
  bool converged = false;          // the iterations met (best is the reading's optimum, not a value below it)
  double best = -kInf;             // normalised
  int binding = -1;                // ratio row index, or −(plain row + 2) when infeasible
  std::vector<double> u;           // per group at the best
  LpRun infeasible_run;
};

// The largest N/D any solid in the region can have, where N/D is an affine function of a centroid:
// D = d·volume on the material (and d_h·volume on the liquid, d_h >= 0), N = the same weights times
// n₀ + n·x, no constants; infinite otherwise. Every ratio row is of that kind (the margins are
// centroids' distances), and a physical solid's centroid lies in the region's box. The generous
// reading with --outer can remove a cell twice (carved and shaved), so its programme reaches
// solids of no mass, whose ratios are rounding noise (4·10¹⁰ on cgal-data_bunny00's roly-poly
// remedy): no solid reaches past this cap.
double ratio_cap(const Form& N, const Form& D, const std::array<Eigen::Vector3d, 8>& region) {
  const double d = D.solid(kIntVolume), d_h = D.hollow(kIntVolume);
  if (N.constant != 0.0 || D.constant != 0.0 || !(d > 0.0) || !(d_h >= 0.0)) return kInf;
  if (!D.solid.tail<9>().isZero() || !D.hollow.tail<9>().isZero() || !N.solid.tail<6>().isZero()) return kInf;
  if (N.hollow != (d_h / d) * N.solid) return kInf;
  double most = -kInf;
  for (const Eigen::Vector3d& x : region) most = std::max(most, (N.solid(kIntVolume) + N.solid.segment<3>(kIntX).dot(x)) / d);
  return most;
}

// Dinkelbach: t ← min_j N_j(u)/D_j(u) after each LP max_u min_j (N_j − t D_j), each ratio capped
// by ratio_cap; stopped short (not converged) once the best reaches `enough`.
MarginSearch best_margin(Solver& solver, Partition& p, const GoalRows& rows, const Frame& f, int cap, double enough = kInf) {
  MarginSearch s;
  std::vector<double> warm(p.groups.size(), 0.0);
  const int nr = static_cast<int>(rows.numerators.size());
  std::vector<double> caps;
  for (int j = 0; j < nr; ++j)
    caps.push_back(ratio_cap(rows.numerators[static_cast<std::size_t>(j)], rows.denominators[static_cast<std::size_t>(j)], f.region));
  // Start from the solid as it is when it meets the plain rows (its margin is one any void beats),
  // else from a margin of minus the diagonal.
  double t = -1.0;
  bool solid_ok = true;
  const Moved none = moved_integrals(p, warm);
  for (const Form& f0 : rows.plain) solid_ok = solid_ok && form_value(f0, f.P0, none) >= 0.0;
  if (solid_ok && nr > 0) {
    t = kInf;
    for (int j = 0; j < nr; ++j)
      t = std::min(t, form_value(rows.numerators[static_cast<std::size_t>(j)], f.P0, none) /
                          form_value(rows.denominators[static_cast<std::size_t>(j)], f.P0, none));
    t = std::max(t, -1.0);
  }
  for (int it = 0; it < cap; ++it) {
    const LpRun run = solver.solve(p, ratio_rows_at(rows, t), nr, true, nullptr, warm);
    if (run.status == LpStatus::infeasible) {
      s.infeasible_run = run;
      return s;
    }
    if (run.status != LpStatus::optimal) break;
    s.feasible = true;
    double t_new = kInf;
    int arg = -1;
    const Moved& moved = solver.moved_at(p, run.u);
    for (int j = 0; j < nr; ++j) {
      const double ratio = std::min(form_value(rows.numerators[static_cast<std::size_t>(j)], f.P0, moved) /
                                        form_value(rows.denominators[static_cast<std::size_t>(j)], f.P0, moved),
                                    caps[static_cast<std::size_t>(j)]);
      if (ratio < t_new) {
        t_new = ratio;
        arg = j;
      }
    }
    if (t_new > s.best) {
      s.best = t_new;
      s.binding = arg;
      s.u = run.u;
    }
    if (run.z <= 1e-12 || t_new - t <= 1e-11) {
      s.converged = true;
      break;
    }
    if (s.best >= enough) break;
    t = t_new;
  }
  return s;
}

// A quadric of the normalised frame in input units about the frame's origin (the rotated pose):
// m_k(s (p − o)) = s^deg(k) m_k(p − o).
Quadric quadric_in_input_units(const Vector10d& frame_coefficients, const Frame& f) {
  const double s = f.scale;
  const int degree[10] = {0, 1, 1, 1, 2, 2, 2, 2, 2, 2};
  Quadric q;
  q.origin = f.origin;
  for (int k = 0; k < 10; ++k) q.coefficients(k) = frame_coefficients(k) * (degree[k] == 0 ? 1.0 : degree[k] == 1 ? s : s * s);
  return q;
}

// The certificate: w >= 0 on rows (each >= 0 when met), checked on every cell of the outer reading
// with a rigorous bound of the quadric over each cube.
ReachCertificate certify(const LpRun& run, const Partition& outer, const Frame& f) {
  ReachCertificate c;
  const double V0 = f.P0(kIntVolume);
  Vector10d gv = Vector10d::Zero(), gb = Vector10d::Zero();
  NeumaierSum total, F0;
  for (std::size_t k = 0; k < run.rows.size() && k < static_cast<std::size_t>(run.weights.size()); ++k) {
    const double w = run.weights(static_cast<Eigen::Index>(k));
    if (w == 0.0) continue;
    const Form& r = run.rows[k];
    gv += w * r.void_coefficients() / V0;
    gb += w * r.solid / V0;
    total.add(w * (r.constant + r.solid.dot(f.P0)) / V0);
    F0.add(w * (r.constant + r.solid.dot(f.P0)) / V0);
  }
  const double h = outer.h, v = h * h * h, half = 0.5 * h;
  for (const FineCell& cell : outer.cells) {
    const Vector10d g = cell.sign == -1 ? gv : cell.sign == 1 ? gb : Vector10d(-gb);
    const Eigen::Vector3d& x = cell.x;
    const double q = g(0) + g(1) * x.x() + g(2) * x.y() + g(3) * x.z() + g(4) * x.x() * x.x() + g(5) * x.y() * x.y() +
                     g(6) * x.z() * x.z() + g(7) * x.x() * x.y() + g(8) * x.y() * x.z() + g(9) * x.z() * x.x();
    const Eigen::Vector3d grad(g(1) + 2.0 * g(4) * x.x() + g(7) * x.y() + g(9) * x.z(),
                               g(2) + 2.0 * g(5) * x.y() + g(7) * x.x() + g(8) * x.z(),
                               g(3) + 2.0 * g(6) * x.z() + g(8) * x.y() + g(9) * x.x());
    const double hess = 2.0 * (std::fabs(g(4)) + std::fabs(g(5)) + std::fabs(g(6))) +
                        2.0 * (std::fabs(g(7)) + std::fabs(g(8)) + std::fabs(g(9)));
    // q on the cube is q(x + d), |d_i| <= h/2: within `spread` of its value at the centre.
    const double spread = half * grad.cwiseAbs().sum() + 0.5 * half * half * hess;
    const double most = q + spread, least = q - spread;
    // The void's part of the integral in this cube is at most ∫ max(0, q) over it: 0 where q is
    // nowhere positive; ∫ q itself, exactly v (q(x) + h²/12 (g₄ + g₅ + g₆)), where q is positive on
    // the whole cube; else at most v · max q. Bounding every cube by v · max q instead counts the
    // spread once per positive cube: on cgal-data_bunny00 standing as a roly-poly, 0.0044 against
    // the programme's −0.042, no proof. Each term is rounded up (1e-12 of itself; `least` must
    // clear its own rounding), far beyond the sums' own error.
    // A void holds at most the cell's share of the cube (cavity/wall_deep_shares.h), so at most
    // share · v · max q of it too.
    if (most > 0.0) {
      const double mean = q + half * half / 3.0 * (g(4) + g(5) + g(6));
      const bool positive = least > 1e-12 * (std::fabs(q) + spread);
      const double at_most = cell.share * most;
      total.add(v * (positive ? std::min(mean, at_most) : at_most) * (1.0 + 1e-12));
    }
    ++c.cells_checked;
  }
  c.present = true;
  c.bound = total.value();
  c.proves = c.bound < -1e-13;
  // void = {q < 0} = {q_v > 0}.
  const Quadric q = quadric_in_input_units(-gv, f);
  c.quadric = q.coefficients;
  c.origin = q.origin;
  const double s = f.scale;
  c.constant = F0.value() / (s * s * s);
  return c;
}

std::string binding_name(const GoalRows& rows, int binding) {
  if (binding >= 0 && binding < static_cast<int>(rows.ratio_names.size())) return rows.ratio_names[static_cast<std::size_t>(binding)];
  return "";
}

// The name of the plain row with the largest weight in an infeasibility certificate.
std::string heaviest_plain(const GoalRows& rows, const LpRun& run) {
  int best = -1;
  const int nr = static_cast<int>(rows.numerators.size());
  for (int k = nr; k < static_cast<int>(run.weights.size()); ++k)
    if (best < 0 || run.weights(k) > run.weights(best)) best = k;
  return best >= 0 ? rows.plain_names[static_cast<std::size_t>(best - nr)] : "";
}

double user_margin(const GoalSpec& goal) {
  return goal.kind == GoalKind::stand || goal.kind == GoalKind::stand_filled ? goal.margin : goal.epsilon;
}

// Lowest cz over the ground (normalised) with every row at the user's margin: Dinkelbach on ∫z / M.
std::optional<double> lowest_cz(Solver& solver, Partition& p, const GoalRows& rows, const Frame& f, double margin,
                                std::vector<double>& u, int cap, Vector10d& void_reduced) {
  const std::vector<Form> constraints = ratio_rows_at(rows, margin);
  const Form Z = solid_form(unit(kIntZ)), M = solid_form(unit(kIntVolume));
  std::vector<double> warm = u;
  double theta = form_value(Z, f.P0, solver.moved_at(p, u)) / form_value(M, f.P0, solver.moved_at(p, u));
  std::optional<double> best;
  for (int it = 0; it < cap; ++it) {
    Form obj;
    obj.solid = -(Z.solid - theta * M.solid);
    // The ratio rows (at the margin) by row generation too: a round base has hundreds of edges.
    const LpRun run = solver.solve(p, constraints, static_cast<int>(rows.numerators.size()), false, &obj, warm);
    if (run.status != LpStatus::optimal) break;
    const double next = form_value(Z, f.P0, solver.moved_at(p, run.u)) / form_value(M, f.P0, solver.moved_at(p, run.u));
    if (!best || next < *best) {
      best = next;
      u = run.u;
      void_reduced = run.void_reduced;
    }
    if (theta - next <= 1e-12) break;
    theta = next;
  }
  return best;
}

std::vector<double> per_cell(const Partition& p, const std::vector<double>& u, int sign, std::size_t count) {
  std::vector<double> out(count, 0.0);
  for (std::size_t g = 0; g < p.groups.size() && g < u.size(); ++g)
    for (int q = p.groups[g].begin; q < p.groups[g].end; ++q) {
      const FineCell& c = p.cells[static_cast<std::size_t>(p.order[static_cast<std::size_t>(q)])];
      if (c.sign == sign) out[static_cast<std::size_t>(c.source)] = u[g];
    }
  return out;
}

// Spin's optimum (Reachability::find_optimum): at the level whose rows a void met, the void that
// leaves the solid's moment ∫z least (the paper's m·cz, its objective's first term), from that
// void's occupancy `warm` (per group of the partition rebuilt here as reachability built it).
void spin_optimum(const CarvableCells& cells, const Frame& f, const ReachabilityOptions& options, const GoalRows& rows,
                  bool band, std::vector<double> warm, Reachability& r) {
  const std::vector<std::int64_t>& writable = options.mid_reading ? cells.mid : cells.inner;
  Partition inner = make_partition(cells, writable, band ? cells.band_inner : std::vector<std::int64_t>{}, {}, f, options.block);
  Solver solver(f, options, r);
  Form low;
  low.solid = -unit(kIntZ);
  const LpRun lowest = solver.solve(inner, rows.plain, 0, false, &low, warm);
  if (lowest.status != LpStatus::optimal) return;
  r.optimum = quadric_in_input_units(-lowest.void_reduced, f);
  r.occupancy = per_cell(inner, lowest.u, -1, writable.size());
  r.band_occupancy = per_cell(inner, lowest.u, 1, cells.band_inner.size());
}

// Where volume's ball starts (ReachabilityOptions::volume_start): the writable cell nearest their
// centroid (a ball about the centroid itself may miss the cells: a torus), or the one farthest
// along `start` of those within a cell of it (first in the list on a tie).
Eigen::Vector3d ball_start(const CarvableCells& cells, const std::vector<std::int64_t>& writable,
                           const std::optional<ReachabilityOptions::Line>& start) {
  if (start) {
    const double h = cells.grid.spacing;
    const Eigen::Vector3d d = start->direction.normalized();
    std::optional<Eigen::Vector3d> best;
    for (std::int64_t cell : writable) {
      const Eigen::Vector3d x = cells.centre(cell), off = x - start->point;
      if ((off - off.dot(d) * d).squaredNorm() > h * h) continue;
      if (!best || x.dot(d) > best->dot(d)) best = x;
    }
    if (best) return *best;
  }
  NeumaierSum sum[3];
  for (std::int64_t cell : writable) {
    const Eigen::Vector3d x = cells.centre(cell);
    for (int a = 0; a < 3; ++a) sum[a].add(x(a));
  }
  const double n = static_cast<double>(writable.size());
  const Eigen::Vector3d centroid(sum[0].value() / n, sum[1].value() / n, sum[2].value() / n);
  Eigen::Vector3d c = cells.centre(writable.front());
  for (std::int64_t cell : writable)
    if ((cells.centre(cell) - centroid).squaredNorm() < (c - centroid).squaredNorm()) c = cells.centre(cell);
  return c;
}

// Volume's optimum (Reachability::find_optimum): the goal places no centre of mass, so the void
// written is a ball clipped to the writable cells that holds the target: the cells nearest its
// start (ball_start), in order of distance (ties by index), the last one part full;
// q = |p − c|² − r², r² between the last cell taken and the next.
void volume_optimum(const CarvableCells& cells, const std::vector<std::int64_t>& writable, double target,
                    const std::optional<ReachabilityOptions::Line>& start, Reachability& r) {
  const double v = cells.cell_volume();
  if (writable.empty() || !(target > 0.0) || !(v > 0.0)) return;
  const Eigen::Vector3d c = ball_start(cells, writable, start);
  std::vector<std::pair<double, std::size_t>> order(writable.size());
  for (std::size_t i = 0; i < writable.size(); ++i) order[i] = {(cells.centre(writable[i]) - c).squaredNorm(), i};
  std::sort(order.begin(), order.end());
  r.occupancy.assign(writable.size(), 0.0);
  double left = target;
  std::size_t taken = 0;
  for (; taken < order.size() && left > 0.0; ++taken) {
    const double part = std::min(1.0, left / v);
    r.occupancy[order[taken].second] = part;
    left -= part * v;
  }
  const double h = cells.grid.spacing;
  const double r2 = taken < order.size() ? 0.5 * (order[taken - 1].first + order[taken].first) : order.back().first + h * h;
  Quadric q;
  q.origin = c;
  q.coefficients << -r2, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0;
  r.optimum = q;
  r.band_occupancy.assign(cells.band_inner.size(), 0.0);
}

// `grid`: the cells' grid, whose box holds every solid they describe (Frame::region).
Frame make_frame(const VolumeIntegrals& input, const Eigen::Matrix3d& R, const Eigen::Vector3d& origin, double diagonal,
                 double top, const NodeGrid& grid) {
  Frame f;
  f.scale = 1.0 / diagonal;
  f.origin = origin;
  f.rotation = R;
  // Rotate: first moments R m, second moments R S Rᵀ, about R·(the input's origin).
  const Vector10d& v = input.values;
  Eigen::Matrix3d S;
  S << v(kIntXX), v(kIntXY), v(kIntZX), v(kIntXY), v(kIntYY), v(kIntYZ), v(kIntZX), v(kIntYZ), v(kIntZZ);
  const Eigen::Vector3d m1 = R * v.segment<3>(kIntX);
  const Eigen::Matrix3d S1 = R * S * R.transpose();
  VolumeIntegrals rotated;
  rotated.origin = R * input.origin;
  rotated.values << v(kIntVolume), m1.x(), m1.y(), m1.z(), S1(0, 0), S1(1, 1), S1(2, 2), S1(0, 1), S1(1, 2), S1(2, 0);
  const VolumeIntegrals shifted = shift_integrals(rotated, origin);
  const double s = f.scale;
  const int degree[10] = {0, 1, 1, 1, 2, 2, 2, 2, 2, 2};
  for (int k = 0; k < 10; ++k) {
    double factor = s * s * s;
    for (int d = 0; d < degree[k]; ++d) factor *= s;
    f.P0(k) = shifted.values(k) * factor;
  }
  f.top = top * s;
  for (int c = 0; c < 8; ++c)
    f.region[static_cast<std::size_t>(c)] =
        f.to_frame(R * grid.position(c & 1 ? grid.nx - 1 : 0, c & 2 ? grid.ny - 1 : 0, c & 4 ? grid.nz - 1 : 0));
  return f;
}

// The generous reading of a goal with a margin (reachability's last part): its best margin, an
// upper bound where it is one, and a certificate at the user's margin.
void read_outer_margin(Solver& solver, const MarginSearch& s, const GoalSpec& goal, const Frame& f, double margin, double tau_out,
                       bool band, const std::vector<double>* part, const ReachabilityOptions& options,
                       const CarvableCells& cells, Reachability& out) {
  solver.forget_partitions();
  Partition outer = make_partition(cells, cells.outer, band ? cells.band_outer : std::vector<std::int64_t>{},
                                   band ? cells.skin_outer : std::vector<std::int64_t>{}, f, options.block, part);
  const GoalRows loose = goal_rows(goal, f, tau_out, 1e-3, 0.0, -1.0);
  // Once a void of the reading clears the user's margin, no certificate can come of it (below).
  const double enough = options.bound_undecided ? kInf : margin + 1e-9;
  const MarginSearch upper = best_margin(solver, outer, loose, f, options.max_dinkelbach, enough);
  // An upper bound only when it is one: Dinkelbach's margins rise to the optimum, so a search
  // stopped short of it bounds nothing from above, and the generous reading holds every void of
  // the mid one, so a figure below the mid reading's best is not its optimum either (the
  // calibration cube's roly-poly: -62.9 against -61.9).
  if (upper.feasible) out.outer_margin_found = upper.best / f.scale;
  if (upper.feasible && upper.converged && (!s.feasible || upper.best >= s.best)) out.best_margin_upper = upper.best / f.scale;
  // The programme at the user's margin can only prove the goal out of reach. When the generous
  // reading already has a void whose every ratio row clears the margin, that void meets it with
  // z >= (best - margin) min_j D_j > 0, so no certificate can come of it (LP tolerances are 1e-11).
  const bool margin_met = upper.feasible && upper.best >= margin + 1e-9;
  if (!margin_met) {
    std::vector<double> warm(outer.groups.size(), 0.0);
    const LpRun at_margin = solver.solve(outer, ratio_rows_at(loose, margin), static_cast<int>(loose.numerators.size()), true,
                                         nullptr, warm);
    if (at_margin.status == LpStatus::infeasible || (at_margin.status == LpStatus::optimal && at_margin.z < 0.0)) {
      out.certificate = certify(at_margin, outer, f);
      out.decided = out.certificate.proves;
    }
  }
  if (out.binding.empty() && upper.feasible) out.binding = binding_name(loose, upper.binding);
}

}  // namespace

Vector10d Quadric::about_zero() const {
  // m(p − o) expanded: the second-order part is unchanged, the lower ones take the shift.
  const Vector10d& c = coefficients;
  const Eigen::Vector3d& o = origin;
  Vector10d a = c;
  a(1) = c(1) - 2.0 * c(4) * o.x() - c(7) * o.y() - c(9) * o.z();
  a(2) = c(2) - 2.0 * c(5) * o.y() - c(7) * o.x() - c(8) * o.z();
  a(3) = c(3) - 2.0 * c(6) * o.z() - c(8) * o.y() - c(9) * o.x();
  a(0) = c(0) - c(1) * o.x() - c(2) * o.y() - c(3) * o.z() + c(4) * o.x() * o.x() + c(5) * o.y() * o.y() +
         c(6) * o.z() * o.z() + c(7) * o.x() * o.y() + c(8) * o.y() * o.z() + c(9) * o.z() * o.x();
  return a;
}

std::string ReachabilityOptions::check() const {
  const ReachabilityOptions& o = *this;
  if (!(o.wall > 0.0) || !std::isfinite(o.wall)) return "the wall must be > 0";
  if (o.outer && !(o.outer_max > 0.0)) return "--outer needs outer_max > 0";
  if (!(o.ground_tol >= 0.0)) return "the ground tolerance must be >= 0";
  if (!(o.cells_per_wall >= 1.25 && o.cells_per_wall <= 8.0)) return "cells per wall must be in [1.25, 8]";
  if (!(o.contour_cells_per_wall >= 1.25 && o.contour_cells_per_wall <= 8.0)) return "the contour's cells per wall must be in [1.25, 8]";
  if (o.block < 1 || o.block > 16 || (o.block & (o.block - 1)) != 0) return "the block must be 1, 2, 4, 8 or 16 cells";
  if (o.max_dinkelbach < 1 || o.max_dinkelbach > 200) return "max_dinkelbach must be in [1, 200]";
  if (o.max_refinements < 0 || o.max_refinements > 200) return "max_refinements must be in [0, 200]";
  if (!(o.axis_tolerance > 0.0 && o.axis_tolerance <= 0.7e-4)) return "the axis tolerance must be in (0, 0.7e-4]";
  if (o.spin_levels < 1 || o.spin_levels > 200) return "spin_levels must be in [1, 200]";
  if (o.share_levels < 0 || o.share_levels > 6) return "share_levels must be in [0, 6]";
  if (o.threads < 1 || o.threads > 64) return "threads must be in [1, 64]";
  return o.lp.check();
}

Reachability reachability(const Mesh& input, const TriangleBvh& input_bvh, const GoalSpec& goal, double ground_z,
                          const Eigen::Vector3d& origin, const ReachabilityOptions& options) {
  if (const std::string problem = options.check(); !problem.empty()) {
    Reachability r;
    r.message = problem;
    return r;
  }
  CarvableCellsOptions co;
  co.wall = options.wall;
  co.cells_per_wall = options.cells_per_wall;
  {
    // The written contour's margin, at its own spacing (cavity/contour_cavity.h).
    const double hc = options.wall / options.contour_cells_per_wall;
    co.node_margin = options.node_margin >= 0.0 ? options.node_margin
                                                : cavity_node_level(options.wall, hc, options.margin_cells, bounding_box(input.V)) - options.wall;
  }
  co.margin_cells = options.margin_cells;
  co.max_nodes = options.max_nodes;
  co.band = options.outer && goal.kind != GoalKind::floating;
  co.outer_max = options.outer_max;
  co.ground_z = ground_z;
  co.ground_tol = options.ground_tol;
  co.threads = options.threads;
  co.strict = !options.mid_reading;  // the mid reading replaces the inner one
  auto cells = std::make_shared<CarvableCells>(carvable_cells(input, input_bvh, co));
  if (!cells->ok) {
    Reachability r;
    r.message = cells->message;
    return r;
  }
  const Eigen::Vector3d lo = input.V.colwise().minCoeff().transpose(), hi = input.V.colwise().maxCoeff().transpose();
  ShareSource shares;
  if (options.share_levels > 0)
    shares = [cells, &input_bvh, wall = options.wall, levels = options.share_levels, threads = options.threads] {
      return wall_deep_shares(*cells, input_bvh, wall, levels, threads).share;
    };
  return reachability(cells, volume_integrals(input), Eigen::Matrix3d::Identity(), goal, ground_z, origin, (hi - lo).norm(),
                      options, shares);
}

Reachability reachability(std::shared_ptr<const CarvableCells> cells, const VolumeIntegrals& input_integrals,
                          const Eigen::Matrix3d& rotation, const GoalSpec& goal, double ground_z,
                          const Eigen::Vector3d& origin, double diagonal, const ReachabilityOptions& options,
                          const ShareSource& shares) {
  Reachability out;
  if (const std::string problem = options.check(); !problem.empty()) {
    out.message = problem;
    return out;
  }
  if (const std::string problem = check_goal_spec(goal); !problem.empty()) {
    out.message = problem;
    return out;
  }
  out.cells = cells;
  const double v = cells->cell_volume();
  const std::vector<std::int64_t>& writable = options.mid_reading ? cells->mid : cells->inner;
  out.carvable_volume = v * static_cast<double>(writable.size());
  out.carvable_volume_outer = v * static_cast<double>(cells->outer.size());
  out.band_volume = v * static_cast<double>(cells->band_inner.size());
  // The highest point over the ground, for the spin's levels: bounded by the cells' reach.
  double top = 0.0;
  for (std::int64_t c : cells->outer) top = std::max(top, (rotation * cells->centre(c)).z() - ground_z);
  const Frame f = make_frame(input_integrals, rotation, origin, diagonal, top, cells->grid);
  out.ok = true;
  const bool band = options.outer && goal.kind != GoalKind::floating;
  // The generous reading with its shell cells counted in part, computed once and only where the
  // whole cells leave the answer open.
  std::vector<double> void_shares;
  auto partial_cells = [&]() -> const std::vector<double>* {
    if (!shares || band) return nullptr;
    if (void_shares.empty()) {
      void_shares = shares();
      out.partial_cells = true;
    }
    return void_shares.size() == cells->outer.size() ? &void_shares : nullptr;
  };
  if (goal.kind == GoalKind::volume) {
    out.reachable = goal.target_volume <= out.carvable_volume;
    out.decided = out.reachable || goal.target_volume > out.carvable_volume_outer;
    if (!out.decided) {
      if (const std::vector<double>* part = partial_cells()) {
        NeumaierSum held;
        for (const double share : *part) held.add(v * share);
        out.carvable_volume_outer = held.value();
        out.decided = goal.target_volume > out.carvable_volume_outer;
      }
    }
    if (out.reachable)
      out.find_optimum = [cells, mid = options.mid_reading, target = goal.target_volume,
                          start = options.volume_start](Reachability& r) {
        volume_optimum(*cells, mid ? cells->mid : cells->inner, target, start, r);
      };
    return out;
  }
  Solver solver(f, options, out);
  Partition inner = make_partition(*cells, writable, band ? cells->band_inner : std::vector<std::int64_t>{}, {}, f, options.block);
  const double margin = user_margin(goal) * f.scale;
  const double tau_in = options.axis_tolerance, tau_out = 1e-4;

  if (goal.kind == GoalKind::spin) {
    std::vector<double> warm;
    for (int l = 0; l < options.spin_levels && !out.reachable; ++l) {
      const double level = f.top * (l + 1.0) / (options.spin_levels + 1.0);
      const GoalRows rows = goal_rows(goal, f, tau_in, 0.0, 0.5e-4, level);
      warm.assign(inner.groups.size(), 0.0);
      const LpRun run = solver.solve(inner, rows.plain, 0, false, nullptr, warm);
      if (run.status == LpStatus::optimal) {
        out.reachable = out.decided = true;
        out.occupancy = per_cell(inner, run.u, -1, writable.size());
        out.band_occupancy = per_cell(inner, run.u, 1, cells->band_inner.size());
        out.find_optimum = [cells, f, options, rows, band, warm = run.u](Reachability& r) {
          spin_optimum(*cells, f, options, rows, band, warm, r);
        };
      }
    }
    auto read_outer = [&](const std::vector<double>* part) {
      solver.forget_partitions();
      Partition outer = make_partition(*cells, cells->outer, band ? cells->band_outer : std::vector<std::int64_t>{},
                                       band ? cells->skin_outer : std::vector<std::int64_t>{}, f, options.block, part);
      const GoalRows rows = goal_rows(goal, f, tau_out, 0.0, 2e-4, -1.0);
      warm.assign(outer.groups.size(), 0.0);
      const LpRun run = solver.solve(outer, rows.plain, 0, false, nullptr, warm);
      if (run.status == LpStatus::infeasible) {
        out.certificate = certify(run, outer, f);
        out.decided = out.certificate.proves;
        out.binding = heaviest_plain(rows, run);
      }
    };
    if (!out.reachable) {
      const std::vector<double>* first = options.shell_in_part_first ? partial_cells() : nullptr;
      read_outer(first);
      if (!out.decided && !first)
        if (const std::vector<double>* part = partial_cells()) read_outer(part);
    }
    return out;
  }

  const GoalRows rows = goal_rows(goal, f, tau_in, 1e-4, 0.0, -1.0);
  MarginSearch s = best_margin(solver, inner, rows, f, options.max_dinkelbach);
  if (s.feasible) {
    out.best_margin = s.best / f.scale;
    out.binding = binding_name(rows, s.binding);
    out.reachable = s.best >= margin;
  } else if (s.infeasible_run.status == LpStatus::infeasible) {
    out.binding = heaviest_plain(rows, s.infeasible_run);
  }
  if (out.reachable) {
    out.decided = true;
    std::vector<double> u = s.u;
    if (options.lowest_cz) {
      Vector10d void_reduced = Vector10d::Zero();
      const std::optional<double> cz = lowest_cz(solver, inner, rows, f, margin, u, options.max_dinkelbach, void_reduced);
      if (cz) {
        out.lowest_cz = *cz / f.scale;
        out.optimum = quadric_in_input_units(-void_reduced, f);
      }
    }
    // The best iterate's groups, unless a later step split blocks (then it is not known per cell).
    if (u.size() == inner.groups.size()) {
      out.occupancy = per_cell(inner, u, -1, writable.size());
      out.band_occupancy = per_cell(inner, u, 1, cells->band_inner.size());
    }
    return out;
  }
  // Not reached on the inner reading: the outer reading's best, and a certificate at the user's
  // margin; where whole cells cannot prove it, again with the shell cells in part.
  const std::vector<double>* first = options.shell_in_part_first ? partial_cells() : nullptr;
  read_outer_margin(solver, s, goal, f, margin, tau_out, band, first, options, *cells, out);
  if (!out.decided && !first)
    if (const std::vector<double>* part = partial_cells()) read_outer_margin(solver, s, goal, f, margin, tau_out, band, part, options, *cells, out);
  return out;
}

}  // namespace offsetopt
