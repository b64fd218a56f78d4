#include "shape/reduced_problem.h"

#include <cmath>
#include <limits>

#include <Eigen/Cholesky>

#include "mass/volume_integrals_gradient.h"
#include "shape/smooth_clamp.h"
#include "optim/transposed_product_10.h"
#include "util/parallel.h"

namespace offsetopt {

namespace {

// Below this size a second thread costs more to wake than it saves: the 770-vertex top's spin
// solve takes 0.048 s on two threads and 0.038 s on one; the 3,010-vertex top's 0.117 s on two
// and 0.132 s on one. The parts are the same either way.
constexpr double kMinParallelVertices = 2000;

}  // namespace

std::string ReducedOptions::check() const {
  const ReducedOptions& options = *this;
  if (!(options.ramp_width > 0.0) || !std::isfinite(options.ramp_width)) return "ramp width must be > 0";
  if (!(options.outer_penalty >= 0.0) || !std::isfinite(options.outer_penalty)) return "penalty must be >= 0";
  if (!(options.overshoot_weight >= 0.0) || !std::isfinite(options.overshoot_weight)) return "overshoot weight must be >= 0";
  if (!(options.start_fraction >= 0.0 && options.start_fraction <= 1.0)) return "start fraction must be in [0, 1]";
  if (options.threads < 1) return "threads must be >= 1";
  return {};
}

ReducedProblem::ReducedProblem(const Mesh& mesh, const OffsetBand& band, const Eigen::MatrixXd& basis,
                               bool identity_basis, const GoalSpec& goal, const ReducedOptions& options)
    : mesh_(mesh),
      band_(band),
      basis_(basis),
      identity_basis_(identity_basis),
      k_(identity_basis ? static_cast<int>(mesh.V.rows()) : static_cast<int>(basis.cols())),
      goal_(goal),
      integral_rows_(goal_integral_rows(goal)),
      goal_equality_count_(static_cast<Eigen::Index>(goal_equality_names(goal).size())),
      options_(options) {
  if (!identity_basis_)
    for (Eigen::Index i = 0; i < mesh_.V.rows(); ++i)
      if (band_.fixed[static_cast<std::size_t>(i)]) basis_.row(i).setZero();
  fixed_outer_integrals_ = volume_integrals(mesh_, Eigen::Vector3d::Zero()).values;
  if (options_.outer) update_outer_inward_limit();
  if (options_.bounds == BoundsMode::hard) build_hard_bounds();
  const Eigen::Index faces = mesh_.F.rows(), half = faces / 2;
  face_parts_[0] = mesh_.F.topRows(half);
  face_parts_[1] = mesh_.F.bottomRows(faces - half);
  vertex_split_[0] = 0;
  vertex_split_[1] = mesh_.V.rows() / 2;
  vertex_split_[2] = mesh_.V.rows();
  if (execution_policy(options_.threads, static_cast<double>(mesh_.V.rows()), kMinParallelVertices) ==
      ExecutionPolicy::parallel)
    pool_ = std::make_unique<WorkerPool>(2, PoolWait::poll_then_sleep);
}

void ReducedProblem::run_parts(const std::function<void(int)>& part) const {
  if (pool_ && !(options_.serial_while && options_.serial_while->load(std::memory_order_relaxed))) {
    pool_->run_parts(2, part);  // both parts, even when the pool got only one thread
  } else {
    part(0);
    part(1);
  }
}

ReducedProblem::~ReducedProblem() = default;

void ReducedProblem::apply_basis_part(const Eigen::VectorXd& coefficients, int part, Eigen::VectorXd& out) const {
  const Eigen::Index begin = vertex_split_[part], end = vertex_split_[part + 1];
  if (!identity_basis_) {
    // Reading Γ (#V by k) is most of this product's cost; each half of the rows is read by one thread.
    out.segment(begin, end - begin).noalias() = basis_.middleRows(begin, end - begin) * coefficients;
    return;
  }
  for (Eigen::Index i = begin; i < end; ++i) out(i) = band_.fixed[static_cast<std::size_t>(i)] ? 0.0 : coefficients(i);
}

template <int Rows>
void ReducedProblem::fill_vertex_rows(Eigen::Index begin, Eigen::Index end) {
  using Column = Eigen::Matrix<double, Rows, 1>;
  const bool outer = options_.outer;
  const double* inner_slope = cache_.inner_slope.data();
  // The face halves' columns are cleared once read: the next evaluation's kernel adds into them
  // without clearing the whole matrices first (they hold +0, as after setZero).
  for (Eigen::Index i = begin; i < end; ++i) {
    double* column = per_vertex_.col(i).data();
    Eigen::Map<Column> inner_a(inner_jacobian_[0].col(i).data()), inner_b(inner_jacobian_[1].col(i).data());
    const Column inner = inner_a + inner_b;
    inner_a.setZero();
    inner_b.setZero();
    Eigen::Map<Column> by_inner_raw(column);
    by_inner_raw = inner * inner_slope[i];
    if (!outer) continue;
    Eigen::Map<Column> outer_a(outer_jacobian_[0].col(i).data()), outer_b(outer_jacobian_[1].col(i).data());
    const Column outer_sum = outer_a + outer_b;
    outer_a.setZero();
    outer_b.setZero();
    Eigen::Map<Column> inner_by_outer_raw(column + Rows), outer_by_outer_raw(column + 2 * Rows);
    inner_by_outer_raw = inner * inner_by_outer_(i);
    outer_by_outer_raw = outer_sum * outer_slope_(i);
  }
}

Eigen::MatrixXd ReducedProblem::project_rows(const Eigen::MatrixXd& per_vertex, Eigen::Index begin,
                                             Eigen::Index end) const {
  const Eigen::Index count = end - begin;
  if (!identity_basis_) return per_vertex.middleCols(begin, count) * basis_.middleRows(begin, count);
  // Γ = I: the columns of this part go to the same columns of the result, fixed ones zeroed.
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(per_vertex.rows(), per_vertex.cols());
  for (Eigen::Index i = begin; i < end; ++i)
    if (!band_.fixed[static_cast<std::size_t>(i)]) out.col(i) = per_vertex.col(i);
  return out;
}

// Inward, the outer surface may use at most half of the free band (hi − δl), so the wall coupling
// lo = δl − δout stays below hi and the inner surface cannot be crossed; in a part left solid
// (δl >= hi) it cannot move inward at all.
void ReducedProblem::update_outer_inward_limit() {
  outer_inward_limit_.resize(mesh_.V.rows());
  for (Eigen::Index i = 0; i < mesh_.V.rows(); ++i) {
    const double free_band = band_.upper(i) - band_.lower(i);
    const double half = free_band > 0.0 ? 0.5 * free_band : 0.0;
    outer_inward_limit_(i) = half < band_.outer_limit(i) ? half : band_.outer_limit(i);
  }
}

void ReducedProblem::set_outer_limit(const Eigen::VectorXd& limit) {
  if (!options_.outer || limit.size() != mesh_.V.rows()) return;
  band_.outer_limit = limit;
  update_outer_inward_limit();
  if (options_.bounds == BoundsMode::hard) build_hard_bounds();
  cache_valid_ = false;
}

void ReducedProblem::build_hard_bounds() {
  const Eigen::Index n = mesh_.V.rows(), k = k_;
  const double inf = std::numeric_limits<double>::infinity();
  if (identity_basis_ && !options_.outer) {
    // Bounds on the variables themselves (see constrained_problem()): no #V by #V matrix.
    hard_lower_ = band_.lower;
    hard_upper_ = band_.upper;
    for (Eigen::Index i = 0; i < n; ++i)
      if (band_.fixed[static_cast<std::size_t>(i)]) {
        hard_lower_(i) = -inf;
        hard_upper_(i) = inf;
      }
    return;
  }
  Eigen::MatrixXd G = identity_basis_ ? Eigen::MatrixXd(Eigen::MatrixXd::Identity(n, n)) : basis_;
  for (Eigen::Index i = 0; i < n; ++i)
    if (band_.fixed[static_cast<std::size_t>(i)]) G.row(i).setZero();
  if (!options_.outer) {
    hard_matrix_ = G;  // δl ≤ Γα ≤ hi: empty where a part is thinner than the wall
    hard_lower_ = band_.lower;
    hard_upper_ = band_.upper;
  } else {
    hard_matrix_ = Eigen::MatrixXd::Zero(3 * n, 2 * k);
    hard_matrix_.block(0, 0, n, k) = G;          // −inf ≤ Γα ≤ hi
    hard_matrix_.block(n, k, n, k) = G;          // −omax ≤ Γβ ≤ omax
    hard_matrix_.block(2 * n, 0, n, k) = G;      // Γα + Γβ ≥ δl
    hard_matrix_.block(2 * n, k, n, k) = G;
    hard_lower_.resize(3 * n);
    hard_upper_.resize(3 * n);
    hard_lower_ << Eigen::VectorXd::Constant(n, -inf), -outer_inward_limit_, band_.lower;
    hard_upper_ << band_.upper, band_.outer_limit, Eigen::VectorXd::Constant(n, inf);
  }
  // Fixed vertices have zero rows: their bounds are relaxed (paper 5.2).
  for (Eigen::Index r = 0; r < hard_matrix_.rows(); ++r)
    if (band_.fixed[static_cast<std::size_t>(r % n)]) {
      hard_lower_(r) = -inf;
      hard_upper_(r) = inf;
    }
}

const ReducedProblem::Evaluation& ReducedProblem::evaluate(const Eigen::VectorXd& x) { return evaluate_with_integrals(x, true); }

bool ReducedProblem::values_at(const Eigen::VectorXd& x, bool all_integrals) const {
  return values_valid_ && cache_.x.size() == x.size() && cache_.x == x && (cache_all_integrals_ || !all_integrals);
}

void ReducedProblem::evaluate_values(const Eigen::VectorXd& x, bool all_integrals) {
  cache_valid_ = false;
  values_valid_ = false;
  const Eigen::Index n = mesh_.V.rows();
  const bool clamp = options_.bounds == BoundsMode::clamp;
  const bool outer = options_.outer;
  const double tau = options_.ramp_width;
  Evaluation& e = cache_;
  e.x = x;
  const Eigen::VectorXd inner_coefficients = x.head(k_);
  const Eigen::VectorXd outer_coefficients = outer ? Eigen::VectorXd(x.tail(k_)) : Eigen::VectorXd();
  raw_inner_.resize(n);
  if (outer) raw_outer_.resize(n);
  const Eigen::VectorXd& raw_inner = raw_inner_;
  const Eigen::VectorXd& raw_outer = raw_outer_;

  // Per-vertex rows, projected onto Γ in one pass: the derivatives of the integrals the goal
  // uses (R of the 10), inner by α; with outer offsets also inner by β (through lo) and outer by
  // β; then the overshoot term's derivative by Γα (and by Γβ).
  const bool overshoot_term = has_overshoot_term();
  const Eigen::Index overshoot_row = first_overshoot_row();
  const Eigen::Index rows = overshoot_row + (overshoot_term ? (outer ? 2 : 1) : 0);
  per_vertex_.resize(rows, n);
  e.inner_offset.resize(n);
  e.inner_slope.resize(n);
  e.outer_offset.resize(n);
  outer_slope_.resize(n);
  inner_by_outer_.resize(n);
  inner_vertices_.resize(n, 3);
  if (outer) outer_vertices_.resize(n, 3);
  if (overshoot_term) overshoot_squares_.resize(outer ? 2 * n : n);
  const double overshoot_weight = overshoot_term ? options_.overshoot_weight / static_cast<double>(n) : 0.0;

  // The raw offsets Γα (and Γβ), then the offsets through the clamp, their slopes (by Γα, and by
  // the outer offset through lo), the surfaces, and the overshoot term μ/n Σ (raw − clamped)² with
  // its derivative: vertex by vertex, in the two fixed vertex halves. A vertex reads only its own
  // raw offsets, so one pass over the parts does it all (one wake of the pool, not three).
  auto vertex_part = [&](int part) {
    apply_basis_part(inner_coefficients, part, raw_inner_);
    if (outer) apply_basis_part(outer_coefficients, part, raw_outer_);
    for (Eigen::Index i = vertex_split_[part]; i < vertex_split_[part + 1]; ++i) {
      const bool fixed = band_.fixed[static_cast<std::size_t>(i)];
      double outer_offset = 0.0, outer_slope = 0.0;
      if (outer && !fixed) {
        if (clamp) {
          outer_offset = smooth_clamp(raw_outer(i), -outer_inward_limit_(i), band_.outer_limit(i), tau, &outer_slope);
        } else {
          outer_offset = raw_outer(i);
          outer_slope = 1.0;
        }
      }
      double inner_offset = 0.0, inner_slope = 0.0, inner_by_outer = 0.0;
      if (!fixed && !clamp) {
        inner_offset = raw_inner(i);
        inner_slope = 1.0;
      } else if (!fixed) {
        const double hi = band_.upper(i);
        const double wanted_lo = band_.lower(i) - outer_offset;
        const double lo = wanted_lo < hi ? wanted_lo : hi;
        double slope_lo = 0.0;
        inner_offset = smooth_clamp(raw_inner(i), lo, hi, tau, &inner_slope, &slope_lo);
        if (wanted_lo < hi) inner_by_outer = -slope_lo * outer_slope;
      }
      e.inner_offset(i) = inner_offset;
      e.inner_slope(i) = inner_slope;
      e.outer_offset(i) = outer_offset;
      outer_slope_(i) = outer_slope;
      inner_by_outer_(i) = inner_by_outer;
      inner_vertices_.row(i) = mesh_.V.row(i) + inner_offset * band_.inner_direction.row(i);
      if (outer) outer_vertices_.row(i) = mesh_.V.row(i) + outer_offset * band_.outer_direction.row(i);
      if (!overshoot_term) continue;
      double by_inner_raw = 0.0, by_outer_raw = 0.0, inner_square = 0.0, outer_square = 0.0;
      if (!fixed) {
        const double inner_excess = raw_inner(i) - inner_offset;
        inner_square = inner_excess * inner_excess;
        by_inner_raw = 2.0 * overshoot_weight * inner_excess * (1.0 - inner_slope);
        if (outer) {
          const double outer_excess = raw_outer(i) - outer_offset;
          outer_square = outer_excess * outer_excess;
          // δin depends on the outer offset through lo; ∂δin/∂(Γβ) = inner_by_outer.
          by_outer_raw = 2.0 * overshoot_weight * (outer_excess * (1.0 - outer_slope) - inner_excess * inner_by_outer);
        }
      }
      per_vertex_(overshoot_row, i) = by_inner_raw;
      if (outer) {
        per_vertex_(overshoot_row + 1, i) = by_outer_raw;
        overshoot_squares_(2 * i) = inner_square;
        overshoot_squares_(2 * i + 1) = outer_square;
      } else {
        overshoot_squares_(i) = inner_square;
      }
    }
  };
  run_parts(vertex_part);
  double overshoot = 0.0;  // summed in vertex order, whatever ran the parts
  for (Eigen::Index j = 0; j < overshoot_squares_.size(); ++j) overshoot += overshoot_squares_(j);

  // The surfaces' integrals and ∂I/∂(offset) per vertex (one pass over the faces), then
  // ∂I/∂(coefficients) through the clamp's slopes projected onto Γ. The work is always cut into
  // the same two parts (halves of the faces, then halves of the vertices), summed in a fixed
  // order, so the result is the same whether the parts run on one thread or two.
  const Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  // Inside the solve the goal reads no more than the first R integrals (goal_integral_rows), so
  // the others are not summed there (they are NaN); an evaluation that leaves this class has all ten.
  const int integral_count = all_integrals ? 10 : integral_rows_;
  Vector10d inner_part_integrals[2], outer_part_integrals[2];
  // The derivative columns hold +0 unless the last evaluation's were never read (a solver asked
  // for values alone there): then the kernel clears them itself.
  const bool columns_zero = !derivatives_pending_;
  auto surface_part = [&](int part) {
    volume_integrals_and_directional_jacobian(inner_vertices_, face_parts_[part], origin, band_.inner_direction,
                                              inner_part_integrals[part], inner_jacobian_[part], integral_rows_,
                                              integral_count, columns_zero);
    if (outer)
      volume_integrals_and_directional_jacobian(outer_vertices_, face_parts_[part], origin, band_.outer_direction,
                                                outer_part_integrals[part], outer_jacobian_[part], integral_rows_,
                                                integral_count, columns_zero);
  };
  run_parts(surface_part);
  derivatives_pending_ = true;
  e.inner_integrals = inner_part_integrals[0] + inner_part_integrals[1];
  e.outer_integrals = outer ? Vector10d(outer_part_integrals[0] + outer_part_integrals[1]) : fixed_outer_integrals_;
  e.goal = evaluate_goal(goal_, e.outer_integrals, Vector10d(e.inner_integrals + inner_integral_shift_));
  e.objective = e.goal.objective;
  if (outer && options_.outer_penalty > 0.0) {
    const double beta1 = x(k_);
    e.objective += options_.outer_penalty * beta1 * beta1;
  }
  if (overshoot_term) e.objective += overshoot_weight * overshoot;
  values_valid_ = true;
  cache_all_integrals_ = all_integrals;
}

const ReducedProblem::Evaluation& ReducedProblem::evaluate_with_integrals(const Eigen::VectorXd& x, bool all_integrals) {
  if (cache_valid_ && values_at(x, all_integrals)) return cache_;
  if (!values_at(x, all_integrals) || !derivatives_pending_) evaluate_values(x, all_integrals);
  Evaluation& e = cache_;
  const bool outer = options_.outer;
  const Eigen::Index R = integral_rows_;
  const Eigen::Index overshoot_row = first_overshoot_row();
  const bool overshoot_term = has_overshoot_term();

  Eigen::MatrixXd projected_part[2];
  auto projection_part = [&](int part) {
    const Eigen::Index begin = vertex_split_[part], end = vertex_split_[part + 1];
    switch (R) {
      case 1: fill_vertex_rows<1>(begin, end); break;
      case 4: fill_vertex_rows<4>(begin, end); break;
      default: fill_vertex_rows<10>(begin, end); break;
    }
    projected_part[part] = project_rows(per_vertex_, begin, end);
  };
  run_parts(projection_part);
  derivatives_pending_ = false;
  const Eigen::MatrixXd projected = projected_part[0] + projected_part[1];
  // The goal's derivatives by the integrals it does not use are exactly 0: those rows stay 0.
  Eigen::Matrix<double, 10, Eigen::Dynamic> inner_by_alpha = Eigen::Matrix<double, 10, Eigen::Dynamic>::Zero(10, k_);
  Eigen::Matrix<double, 10, Eigen::Dynamic> inner_by_beta, outer_by_beta;
  inner_by_alpha.topRows(R) = projected.topRows(R);
  if (outer) {
    inner_by_beta.setZero(10, k_);
    outer_by_beta.setZero(10, k_);
    inner_by_beta.topRows(R) = projected.middleRows(R, R);
    outer_by_beta.topRows(R) = projected.middleRows(2 * R, R);
  }

  const int nv = num_variables();
  // w_in · ∂I_in/∂α, and with outer offsets w_out · ∂I_out/∂β + w_in · ∂I_in/∂β, summed as Eigen's
  // row-vector products sum them (transposed_product_10) but without a temporary per row: a goal
  // has up to about 130 rows, and this part of an evaluation runs on one thread.
  Eigen::Matrix<double, 1, Eigen::Dynamic> by_alpha(k_), by_outer(k_), by_inner(k_);
  auto chain = [&](const Eigen::Matrix<double, 1, 20>& weights, auto&& g) {
    const Eigen::Matrix<double, 10, 1> w_out = weights.head<10>().transpose(), w_in = weights.tail<10>().transpose();
    transposed_product_10(inner_by_alpha, w_in, by_alpha.data());
    g.head(k_) = by_alpha;
    if (!options_.outer) return;
    transposed_product_10(outer_by_beta, w_out, by_outer.data());
    transposed_product_10(inner_by_beta, w_in, by_inner.data());
    g.tail(k_) = by_outer + by_inner;
  };
  e.objective_gradient.resize(nv);
  chain(e.goal.objective_gradient.transpose(), e.objective_gradient.transpose());
  if (outer && options_.outer_penalty > 0.0) e.objective_gradient(k_) += 2.0 * options_.outer_penalty * x(k_);
  if (overshoot_term) {
    e.objective_gradient.head(k_) += projected.row(overshoot_row).transpose();
    if (outer) e.objective_gradient.tail(k_) += projected.row(overshoot_row + 1).transpose();
  }
  e.equality_jacobian.resize(e.goal.equality.size(), nv);
  for (Eigen::Index r = 0; r < e.goal.equality.size(); ++r) chain(e.goal.equality_jacobian.row(r), e.equality_jacobian.row(r));
  e.inequality_jacobian.resize(e.goal.inequality.size(), nv);
  for (Eigen::Index r = 0; r < e.goal.inequality.size(); ++r)
    chain(e.goal.inequality_jacobian.row(r), e.inequality_jacobian.row(r));
  cache_valid_ = true;
  return e;
}

template <int Rows>
void ReducedProblem::combine_vertex_rows(const Vector20d& weights, double objective_weight, Eigen::Index begin,
                                         Eigen::Index end) {
  using Column = Eigen::Matrix<double, Rows, 1>;
  const bool outer = options_.outer;
  const Column w_out = weights.head<Rows>(), w_in = weights.segment<Rows>(10);
  const Eigen::Index overshoot_row = first_overshoot_row();
  const bool overshoot_term = has_overshoot_term();
  // Like fill_vertex_rows, the face halves' columns are cleared once read.
  for (Eigen::Index i = begin; i < end; ++i) {
    Eigen::Map<Column> inner_a(inner_jacobian_[0].col(i).data()), inner_b(inner_jacobian_[1].col(i).data());
    const double along_inner = w_in.dot(Column(inner_a + inner_b));
    inner_a.setZero();
    inner_b.setZero();
    double by_alpha = along_inner * cache_.inner_slope(i);
    if (overshoot_term) by_alpha += objective_weight * per_vertex_(overshoot_row, i);
    combined_(0, i) = by_alpha;
    if (!outer) continue;
    Eigen::Map<Column> outer_a(outer_jacobian_[0].col(i).data()), outer_b(outer_jacobian_[1].col(i).data());
    const double along_outer = w_out.dot(Column(outer_a + outer_b));
    outer_a.setZero();
    outer_b.setZero();
    double by_beta = along_inner * inner_by_outer_(i) + along_outer * outer_slope_(i);
    if (overshoot_term) by_beta += objective_weight * per_vertex_(overshoot_row + 1, i);
    combined_(1, i) = by_beta;
  }
}

void ReducedProblem::weighted_gradient(const Eigen::VectorXd& x, double objective_weight, const Eigen::VectorXd& row_weights,
                                       Eigen::VectorXd& grad) {
  const Eigen::Index ne = goal_equality_count_;
  if (cache_valid_ && values_at(x, false)) {  // every row's derivatives are there already
    grad = objective_weight * cache_.objective_gradient;
    grad.noalias() += cache_.equality_jacobian.transpose() * row_weights.head(ne);
    grad.noalias() += cache_.inequality_jacobian.transpose() * row_weights.tail(row_weights.size() - ne);
    return;
  }
  if (!values_at(x, false) || !derivatives_pending_) evaluate_values(x, false);
  const GoalValues& goal = cache_.goal;
  Vector20d weights = objective_weight * goal.objective_gradient;
  for (Eigen::Index r = 0; r < goal.equality.size(); ++r) weights += row_weights(r) * goal.equality_jacobian.row(r).transpose();
  for (Eigen::Index r = 0; r < goal.inequality.size(); ++r)
    weights += row_weights(ne + r) * goal.inequality_jacobian.row(r).transpose();
  const bool outer = options_.outer;
  combined_.resize(outer ? 2 : 1, mesh_.V.rows());
  Eigen::MatrixXd projected_part[2];
  run_parts([&](int part) {
    const Eigen::Index begin = vertex_split_[part], end = vertex_split_[part + 1];
    switch (integral_rows_) {
      case 1: combine_vertex_rows<1>(weights, objective_weight, begin, end); break;
      case 4: combine_vertex_rows<4>(weights, objective_weight, begin, end); break;
      default: combine_vertex_rows<10>(weights, objective_weight, begin, end); break;
    }
    projected_part[part] = project_rows(combined_, begin, end);
  });
  derivatives_pending_ = false;
  const Eigen::MatrixXd projected = projected_part[0] + projected_part[1];  // 1 or 2 rows by k
  grad.resize(num_variables());
  grad.head(k_) = projected.row(0).transpose();
  if (outer) grad.tail(k_) = projected.row(1).transpose();
  if (outer && options_.outer_penalty > 0.0) grad(k_) += objective_weight * 2.0 * options_.outer_penalty * x(k_);
}

void ReducedProblem::set_inner_integral_shift(const Vector10d& shift) {
  inner_integral_shift_ = shift;
  cache_valid_ = false;
}

void ReducedProblem::set_goal_margins(double margin, double epsilon) {
  goal_.margin = margin;
  goal_.epsilon = epsilon;
  cache_valid_ = false;
}

Eigen::VectorXd ReducedProblem::start_point() const {
  const Eigen::Index n = mesh_.V.rows();
  Eigen::VectorXd target(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double hi = band_.upper(i);
    const double lo = band_.lower(i) < hi ? band_.lower(i) : hi;
    target(i) = band_.fixed[static_cast<std::size_t>(i)] ? 0.0 : lo + options_.start_fraction * (hi - lo);
  }
  Eigen::VectorXd x = Eigen::VectorXd::Zero(num_variables());
  if (identity_basis_) {
    x.head(k_) = target;
  } else {
    // Least squares Γα ≈ target; a tiny ridge keeps columns zeroed by fixed regions harmless.
    Eigen::MatrixXd normal = basis_.transpose() * basis_;
    normal.diagonal().array() += 1e-12 * (1.0 + normal.diagonal().maxCoeff());
    x.head(k_) = normal.ldlt().solve(basis_.transpose() * target);
  }
  return x;
}

ConstrainedProblem ReducedProblem::constrained_problem() {
  ConstrainedProblem p;
  p.num_variables = num_variables();
  p.objective = [this](const Eigen::VectorXd& x, Eigen::VectorXd& grad) {
    const Evaluation& e = evaluate_with_integrals(x, false);
    grad = e.objective_gradient;
    return e.objective;
  };
  const std::size_t eq = goal_equality_names(goal_).size(), ineq = goal_inequality_names(goal_).size();
  p.num_equality = static_cast<int>(eq);
  p.equality = [this](const Eigen::VectorXd& x, Eigen::VectorXd& values, Eigen::MatrixXd& jacobian) {
    const Evaluation& e = evaluate_with_integrals(x, false);
    values = e.goal.equality;
    jacobian = e.equality_jacobian;
  };
  p.num_inequality = static_cast<int>(ineq);
  p.inequality = [this](const Eigen::VectorXd& x, Eigen::VectorXd& values, Eigen::MatrixXd& jacobian) {
    const Evaluation& e = evaluate_with_integrals(x, false);
    values = e.goal.inequality;
    jacobian = e.inequality_jacobian;
  };
  // Inside the subproblems: the values, then one combined gradient (weighted_gradient).
  p.values = [this, eq](const Eigen::VectorXd& x, Eigen::VectorXd& rows) {
    if (!values_at(x, false)) evaluate_values(x, false);
    rows.head(static_cast<Eigen::Index>(eq)) = cache_.goal.equality;
    rows.tail(rows.size() - static_cast<Eigen::Index>(eq)) = cache_.goal.inequality;
    return cache_.objective;
  };
  p.weighted_gradient = [this](const Eigen::VectorXd& x, double objective_weight, const Eigen::VectorXd& row_weights,
                               Eigen::VectorXd& grad) { weighted_gradient(x, objective_weight, row_weights, grad); };
  if (options_.bounds == BoundsMode::hard && identity_basis_ && !options_.outer) {
    // Per vertex (paper eq. 1) the rows δl ≤ δ ≤ hi are bounds on the variables themselves:
    // L-BFGS-B keeps them exactly, with no multipliers to find. In a part left solid (δl > hi)
    // the box is empty and the solver reports the bounds as unsatisfiable.
    p.lower = hard_lower_;
    p.upper = hard_upper_;
  } else if (options_.bounds == BoundsMode::hard) {
    p.linear_matrix = &hard_matrix_;
    p.linear_lower = hard_lower_;
    p.linear_upper = hard_upper_;
  }
  return p;
}

}  // namespace offsetopt
