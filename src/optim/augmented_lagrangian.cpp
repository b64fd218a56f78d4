#include "optim/augmented_lagrangian.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "util/neumaier_sum.h"

namespace offsetopt {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Restarts of the least-violation solve while each halves the violation (see the infeasibility
// test in the outer loop).
constexpr int kMaxLeastViolationRestarts = 10;

double clamp_to(double v, double lo, double hi) { return std::min(hi, std::max(lo, v)); }

// Evaluates f and all nonlinear constraints at one point, with ∇f and their Jacobian (`at`) or,
// when the problem has `values` and `weighted_gradient`, without them (`values_at`, then
// `gradient` for one combination). A x is added by linear_pass. Keeps the last point, so the
// outer loop reads the values at the subproblem's solution for free.
class Evaluator {
 public:
  Evaluator(const ConstrainedProblem& p, int n, int num_linear)
      : grad(n),
        c(p.num_equality + p.num_inequality),
        jac(p.num_equality + p.num_inequality, n),
        ax(num_linear),
        p_(p),
        ne_(p.num_equality),
        ni_(p.num_inequality),
        ce_(p.num_equality),
        ci_(p.num_inequality),
        je_(p.num_equality, n),
        ji_(p.num_inequality, n),
        combined_(p.values && p.weighted_gradient) {}

  // Everything at x, derivatives included. Returns whether everything is finite.
  bool at(const Eigen::VectorXd& point) {
    if (valid_ && full_ && point.size() == x.size() && point == x) return finite;
    x = point;
    valid_ = true;
    full_ = true;
    ++count;
    f = p_.objective(x, grad);
    if (ne_ > 0) {
      ce_.setZero();
      je_.setZero();
      p_.equality(x, ce_, je_);
      c.head(ne_) = ce_;
      jac.topRows(ne_) = je_;
    }
    if (ni_ > 0) {
      ci_.setZero();
      ji_.setZero();
      p_.inequality(x, ci_, ji_);
      c.tail(ni_) = ci_;
      jac.bottomRows(ni_) = ji_;
    }
    finite = std::isfinite(f) && grad.allFinite() && c.allFinite() && jac.allFinite();
    linear_done = false;
    return finite;
  }

  // f and the rows at x (everything, when the problem has no `values`). Returns whether they are
  // finite.
  bool values_at(const Eigen::VectorXd& point) {
    if (!combined_) return at(point);
    if (valid_ && point.size() == x.size() && point == x) return finite;
    x = point;
    valid_ = true;
    full_ = false;
    ++count;
    f = p_.values(x, c);
    finite = std::isfinite(f) && c.allFinite();
    linear_done = false;
    return finite;
  }

  // objective_weight ∇f + J^T w at the last point, into out; false when not finite.
  bool gradient(double objective_weight, const Eigen::VectorXd& w, Eigen::VectorXd& out) {
    if (full_) {
      if (objective_weight == 0.0) {
        out.setZero();
      } else {
        out = objective_weight * grad;
      }
      if (ne_ + ni_ > 0) out.noalias() += jac.transpose() * w;
      return true;  // `at` checked them
    }
    p_.weighted_gradient(x, objective_weight, w, out);
    return out.allFinite();
  }

  int count = 0;
  Eigen::VectorXd x;
  double f = 0.0;
  bool finite = false;
  bool linear_done = false;  // ax holds A x for this x (written by linear_pass)
  Eigen::VectorXd grad;      // ∇f, valid after `at`
  Eigen::VectorXd c;         // nonlinear rows: equalities then inequalities
  Eigen::MatrixXd jac;       // their Jacobian, valid after `at`
  Eigen::VectorXd ax;        // linear rows, A x (valid when linear_done)

 private:
  const ConstrainedProblem& p_;
  int ne_, ni_;
  bool valid_ = false;
  bool full_ = false;  // grad and jac belong to x
  Eigen::VectorXd ce_, ci_;
  Eigen::MatrixXd je_, ji_;
  bool combined_;
};

// One pass over A in blocks of rows: ax = A x, then with row weights w_j = weight(j, (A x)_j)
// adds A^T w to grad while the block is still in cache (A is streamed once per evaluation, not
// twice). Blocks whose weights are all zero (inactive rows) skip the second product. The block
// size depends only on the number of columns, so the summation order is fixed.
template <class Weight>
void linear_pass(const Eigen::MatrixXd& a, const Eigen::VectorXd& x, Eigen::VectorXd& ax,
                 Eigen::VectorXd& grad, Weight&& weight) {
  const Eigen::Index m = a.rows();
  const Eigen::Index block = std::max<Eigen::Index>(64, 16384 / std::max<Eigen::Index>(1, a.cols()));
  Eigen::VectorXd w(block);
  for (Eigen::Index r0 = 0; r0 < m; r0 += block) {
    const Eigen::Index nb = std::min(block, m - r0);
    const auto rows = a.middleRows(r0, nb);
    ax.segment(r0, nb).noalias() = rows * x;
    bool any = false;
    for (Eigen::Index j = 0; j < nb; ++j) {
      w(j) = weight(r0 + j, ax(r0 + j));
      any = any || w(j) != 0.0;
    }
    if (any) grad.noalias() += rows.transpose() * w.head(nb);
  }
}

struct Rows {
  Eigen::VectorXd lo, hi, scale;  // nonlinear rows (unscaled bounds)
  Eigen::VectorXd lin_scale;      // linear rows
};

// Measures at the evaluator's point, for multipliers nu_bar (scaled) and penalty rho.
struct Measures {
  double violation = 0.0;         // unscaled ∞-norm
  double scaled_violation = 0.0;  // scaled ∞-norm
  double v = 0.0;                 // feasibility-complementarity measure V
  double complementarity = 0.0;
  Eigen::VectorXd nu;             // updated scaled multipliers (nonlinear rows, then linear)
};

}  // namespace

std::string AlOptions::check() const {
  auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
  if (!positive(feasibility_tolerance)) return "feasibility_tolerance must be > 0";
  if (!positive(stationarity_tolerance)) return "stationarity_tolerance must be > 0";
  if (!positive(complementarity_tolerance)) return "complementarity_tolerance must be > 0";
  if (max_outer_iterations < 1) return "max_outer_iterations must be >= 1";
  if (max_evaluations < 1) return "max_evaluations must be >= 1";
  if (!(initial_penalty >= 0.0) || !std::isfinite(initial_penalty))
    return "initial_penalty must be >= 0 (0: automatic)";
  if (!(penalty_increase > 1.0) || !std::isfinite(penalty_increase))
    return "penalty_increase must be > 1";
  if (!(required_decrease > 0.0) || !(required_decrease < 1.0))
    return "required_decrease must be in (0, 1)";
  if (!positive(max_penalty)) return "max_penalty must be > 0";
  if (!positive(max_multiplier)) return "max_multiplier must be > 0";
  if (!(scale_floor >= 0.0) || !std::isfinite(scale_floor)) return "scale_floor must be >= 0";
  if (!positive(initial_inner_tolerance)) return "initial_inner_tolerance must be > 0";
  if (!(inner_tolerance_decrease > 0.0) || !(inner_tolerance_decrease <= 1.0))
    return "inner_tolerance_decrease must be in (0, 1]";
  if (infeasibility_patience < 1) return "infeasibility_patience must be >= 1";
  if (stall_patience < 1) return "stall_patience must be >= 1";
  if (!(clear_violation_factor >= 0.0)) return "clear_violation_factor must be >= 0";
  if (!(hand_off_violation >= 0.0) || !std::isfinite(hand_off_violation)) return "hand_off_violation must be >= 0";
  const std::string inner_problem = inner.check();
  if (!inner_problem.empty()) return "inner: " + inner_problem;
  return std::string();
}

const char* to_string(AlStatus status) {
  switch (status) {
    case AlStatus::converged: return "converged";
    case AlStatus::infeasible: return "infeasible";
    case AlStatus::stalled: return "stalled";
    case AlStatus::max_outer_iterations: return "max-outer-iterations";
    case AlStatus::max_evaluations: return "max-evaluations";
    case AlStatus::stopped: return "stopped";
    case AlStatus::handed_off: return "handed-off";
    case AlStatus::numerical_issue: return "numerical-issue";
    case AlStatus::invalid_input: return "invalid-input";
  }
  return "unknown";
}

namespace {

// What is wrong with the problem, the start point or the options; empty when usable.
std::string problem_error(const ConstrainedProblem& problem, const Eigen::VectorXd& x0, const AlOptions& params) {
  const int n = problem.num_variables;
  const int ne = problem.num_equality;
  const int ni = problem.num_inequality;
  const Eigen::MatrixXd* a = problem.linear_matrix;
  const Eigen::Index m = a ? a->rows() : 0;
  std::string msg = params.check();
  if (msg.empty() && n < 1) msg = "num_variables must be >= 1";
  if (msg.empty() && x0.size() != n) msg = "start point has the wrong length";
  if (msg.empty() && !x0.allFinite()) msg = "start point not finite";
  if (msg.empty() && !problem.objective) msg = "no objective function";
  if (msg.empty() && (ne < 0 || ni < 0)) msg = "negative constraint count";
  if (msg.empty() && ne > 0 && !problem.equality) msg = "num_equality > 0 without a function";
  if (msg.empty() && ni > 0 && !problem.inequality) msg = "num_inequality > 0 without a function";
  if (msg.empty() && static_cast<bool>(problem.values) != static_cast<bool>(problem.weighted_gradient))
    msg = "values and weighted_gradient come together";
  if (msg.empty() && ((problem.lower.size() != 0 && problem.lower.size() != n) ||
                      (problem.upper.size() != 0 && problem.upper.size() != n)))
    msg = "bounds must be empty or of length num_variables";
  if (msg.empty() && a && a->cols() != n) msg = "linear_matrix must have num_variables columns";
  if (msg.empty() && (problem.linear_lower.size() != m || problem.linear_upper.size() != m))
    msg = "linear bounds must have one entry per row of linear_matrix";
  if (msg.empty() && a && !a->allFinite()) msg = "linear_matrix not finite";
  if (!msg.empty()) return msg;
  const Eigen::VectorXd lower = problem.lower.size() ? problem.lower : Eigen::VectorXd::Constant(n, -kInf);
  const Eigen::VectorXd upper = problem.upper.size() ? problem.upper : Eigen::VectorXd::Constant(n, kInf);
  for (int i = 0; msg.empty() && i < n; ++i) {
    if (std::isnan(lower(i)) || std::isnan(upper(i)) || lower(i) > upper(i) || lower(i) == kInf || upper(i) == -kInf)
      msg = "bounds of variable " + std::to_string(i) + " are empty or NaN";
  }
  for (Eigen::Index j = 0; msg.empty() && j < m; ++j) {
    const double lo = problem.linear_lower(j);
    const double hi = problem.linear_upper(j);
    if (std::isnan(lo) || std::isnan(hi) || lo > hi || lo == kInf || hi == -kInf)
      msg = "bounds of linear row " + std::to_string(j) + " are empty or NaN";
  }
  if (msg.empty() && params.initial_equality_multipliers.size() != 0 && params.initial_equality_multipliers.size() != ne)
    msg = "initial_equality_multipliers has " + std::to_string(params.initial_equality_multipliers.size()) +
          " entries for " + std::to_string(ne) + " equality constraints";
  if (msg.empty() && params.initial_inequality_multipliers.size() != 0 &&
      params.initial_inequality_multipliers.size() != ni)
    msg = "initial_inequality_multipliers has " + std::to_string(params.initial_inequality_multipliers.size()) +
          " entries for " + std::to_string(ni) + " inequality constraints";
  if (msg.empty() && !(params.initial_equality_multipliers.allFinite() && params.initial_inequality_multipliers.allFinite()))
    msg = "initial multipliers must be finite";
  return msg;
}

// One run of the method on a problem problem_error accepts: the scaled rows, the multipliers and
// the penalty as state; each step of the outer loop a method (the shape of LBFGS++'s solvers).
class AugmentedLagrangian {
 public:
  AugmentedLagrangian(const ConstrainedProblem& problem, const Eigen::VectorXd& x0, const AlOptions& params)
      : problem_(problem),
        params_(params),
        n_(problem.num_variables),
        ne_(problem.num_equality),
        ni_(problem.num_inequality),
        nn_(ne_ + ni_),
        a_(problem.linear_matrix),
        m_(a_ ? a_->rows() : 0),
        lower_(problem.lower.size() ? problem.lower : Eigen::VectorXd::Constant(n_, -kInf)),
        upper_(problem.upper.size() ? problem.upper : Eigen::VectorXd::Constant(n_, kInf)),
        ev_(problem, n_, static_cast<int>(m_)) {
    res_.x = x0;
    x_ = x0;
  }

  AlResult minimize();

 private:
  bool start();
  void choose_initial_penalty();
  Measures measures() const;
  AlResult fill_result(AlStatus status, const Measures& meas);
  double subproblem(const Eigen::VectorXd& xs, Eigen::VectorXd& grad);
  double violation(const Eigen::VectorXd& xs, Eigen::VectorXd& grad);
  bool evaluate_all(const Eigen::VectorXd& xs);
  void report_iteration(int outer, const LbfgsbResult& sub, const Measures& meas) const;
  bool reach_least_violation(double feas, const Measures& meas, double stationarity);

  const ConstrainedProblem& problem_;
  const AlOptions& params_;
  const int n_, ne_, ni_, nn_;
  const Eigen::MatrixXd* a_;
  const Eigen::Index m_;
  const Eigen::VectorXd lower_, upper_;
  Evaluator ev_;
  AlResult res_;
  Eigen::VectorXd x_;
  Rows rows_;
  double sf_ = 1.0;         // objective scale
  Eigen::VectorXd nu_bar_;  // multipliers (scaled), nonlinear rows then linear rows
  Eigen::VectorXd nu_;
  Eigen::VectorXd shift_;   // nu_bar / rho
  Eigen::VectorXd w_nl_;
  double rho_ = 1.0;        // penalty
};

// Clamps the start into the box, evaluates it and scales the rows from it; false when anything
// is not finite there.
bool AugmentedLagrangian::start() {
  rows_.lo.resize(nn_);
  rows_.hi.resize(nn_);
  for (int i = 0; i < nn_; ++i) {
    rows_.lo(i) = i < ne_ ? 0.0 : -kInf;
    rows_.hi(i) = 0.0;
  }
  for (int i = 0; i < n_; ++i) x_(i) = clamp_to(x_(i), lower_(i), upper_(i));
  bool start_finite = ev_.at(x_);
  if (m_ > 0) {
    ev_.ax.noalias() = (*a_) * x_;
    ev_.linear_done = true;
    start_finite = start_finite && ev_.ax.allFinite();
  }

  // Scaling from the start point.
  auto scale_of = [&](double gradient_norm) {
    if (params_.scale_floor == 0.0) return 1.0;
    return 1.0 / std::max(params_.scale_floor, gradient_norm);
  };
  sf_ = start_finite ? scale_of(ev_.grad.lpNorm<Eigen::Infinity>()) : 1.0;
  rows_.scale.resize(nn_);
  for (int i = 0; i < nn_; ++i) rows_.scale(i) = start_finite ? scale_of(ev_.jac.row(i).lpNorm<Eigen::Infinity>()) : 1.0;
  rows_.lin_scale.resize(m_);
  for (Eigen::Index j = 0; j < m_; ++j) rows_.lin_scale(j) = scale_of(a_->row(j).lpNorm<Eigen::Infinity>());

  nu_bar_ = Eigen::VectorXd::Zero(nn_ + m_);
  nu_ = nu_bar_;
  // A warm start converts the unscaled multipliers (see fill_result); inequality ones are >= 0.
  for (int i = 0; i < nn_; ++i) {
    const bool eq = i < ne_;
    const Eigen::VectorXd& given = eq ? params_.initial_equality_multipliers : params_.initial_inequality_multipliers;
    if (given.size() == 0) continue;
    const double unscaled = given(eq ? i : i - ne_);
    nu_(i) = (eq ? unscaled : std::max(0.0, unscaled)) * sf_ / rows_.scale(i);
  }
  shift_ = Eigen::VectorXd::Zero(nn_ + m_);
  w_nl_.resize(nn_);
  return start_finite;
}

void AugmentedLagrangian::choose_initial_penalty() {
  const Eigen::VectorXd& lin_lo = problem_.linear_lower;
  const Eigen::VectorXd& lin_hi = problem_.linear_upper;
  if (params_.initial_penalty > 0.0) {
    rho_ = params_.initial_penalty;
  } else {
    double half_sq = 0.0;
    auto add_sq = [&](double value, double lo, double hi, double s) {
      const double viol = value < lo ? lo - value : (value > hi ? value - hi : 0.0);
      half_sq += 0.5 * (s * viol) * (s * viol);
    };
    for (int i = 0; i < nn_; ++i) add_sq(ev_.c(i), rows_.lo(i), rows_.hi(i), rows_.scale(i));
    for (Eigen::Index j = 0; j < m_; ++j) add_sq(ev_.ax(j), lin_lo(j), lin_hi(j), rows_.lin_scale(j));
    rho_ = clamp_to(10.0 * std::max(1.0, std::fabs(sf_ * ev_.f)) / std::max(1.0, half_sq), 1e-8, 1e8);
  }
  rho_ = std::min(rho_, params_.max_penalty);
}

Measures AugmentedLagrangian::measures() const {
  Measures out;
  out.nu.resize(nn_ + m_);
  auto row = [&](Eigen::Index k, double value, double lo, double hi, double s) {
    const double viol = value < lo ? lo - value : (value > hi ? value - hi : 0.0);
    out.violation = std::max(out.violation, viol);
    out.scaled_violation = std::max(out.scaled_violation, s * viol);
    const double sc = s * value, slo = s * lo, shi = s * hi;
    const double t = sc + shift_(k);
    const double pt = clamp_to(t, slo, shi);
    out.v = std::max(out.v, std::fabs(sc - pt));
    const double nu_k = rho_ * (t - pt);
    out.nu(k) = nu_k;
    double gap = 0.0;
    if (nu_k > 0.0) gap = std::fabs(shi - sc);
    if (nu_k < 0.0) gap = std::fabs(sc - slo);
    out.complementarity = std::max(out.complementarity, std::min(std::fabs(nu_k), gap));
  };
  for (int i = 0; i < nn_; ++i) row(i, ev_.c(i), rows_.lo(i), rows_.hi(i), rows_.scale(i));
  for (Eigen::Index j = 0; j < m_; ++j)
    row(nn_ + j, ev_.ax(j), problem_.linear_lower(j), problem_.linear_upper(j), rows_.lin_scale(j));
  return out;
}

AlResult AugmentedLagrangian::fill_result(AlStatus status, const Measures& meas) {
  res_.status = status;
  res_.x = ev_.x;
  res_.f = ev_.f;
  res_.max_violation = meas.violation;
  res_.scaled_violation = meas.scaled_violation;
  res_.complementarity = meas.complementarity;
  res_.penalty = rho_;
  res_.evaluations = ev_.count;
  res_.equality_multipliers.resize(ne_);
  res_.inequality_multipliers.resize(ni_);
  res_.linear_multipliers.resize(m_);
  for (int i = 0; i < nn_; ++i) {
    const double unscaled = nu_(i) * rows_.scale(i) / sf_;
    if (i < ne_) {
      res_.equality_multipliers(i) = unscaled;
    } else {
      res_.inequality_multipliers(i - ne_) = unscaled;
    }
  }
  for (Eigen::Index j = 0; j < m_; ++j) res_.linear_multipliers(j) = nu_(nn_ + j) * rows_.lin_scale(j) / sf_;
  res_.equality_values = ev_.c.head(ne_);
  res_.inequality_values = ev_.c.tail(ni_);
  return res_;
}

// The subproblem: the scaled augmented Lagrangian, minimised over the box.
double AugmentedLagrangian::subproblem(const Eigen::VectorXd& xs, Eigen::VectorXd& grad) {
  if (!ev_.values_at(xs)) {
    grad.setConstant(kNaN);
    return kNaN;
  }
  const Eigen::VectorXd& lin_lo = problem_.linear_lower;
  const Eigen::VectorXd& lin_hi = problem_.linear_upper;
  NeumaierSum sum;  // the linear block adds up to 10⁶ penalty terms per evaluation
  sum.add(sf_ * ev_.f);
  for (int i = 0; i < nn_; ++i) {
    const double s = rows_.scale(i);
    const double t = s * ev_.c(i) + shift_(i);
    const double dv = t - clamp_to(t, s * rows_.lo(i), s * rows_.hi(i));
    sum.add(0.5 * rho_ * dv * dv);
    w_nl_(i) = rho_ * dv * s;
  }
  if (!ev_.gradient(sf_, w_nl_, grad)) {
    grad.setConstant(kNaN);
    return kNaN;
  }
  if (m_ > 0) {
    linear_pass(*a_, xs, ev_.ax, grad, [&](Eigen::Index j, double value) {
      const double s = rows_.lin_scale(j);
      const double t = s * value + shift_(nn_ + j);
      const double dv = t - clamp_to(t, s * lin_lo(j), s * lin_hi(j));
      if (dv == 0.0) return 0.0;
      sum.add(0.5 * rho_ * dv * dv);
      return rho_ * dv * s;
    });
    ev_.linear_done = true;
    if (!ev_.ax.allFinite()) {
      grad.setConstant(kNaN);
      return kNaN;
    }
  }
  return sum.value();
}

// ½ Σ (s_i dist(c_i, [lo_i, hi_i]))²: minimised over the box to find a least-violation point.
double AugmentedLagrangian::violation(const Eigen::VectorXd& xs, Eigen::VectorXd& grad) {
  if (!ev_.values_at(xs)) {
    grad.setConstant(kNaN);
    return kNaN;
  }
  const Eigen::VectorXd& lin_lo = problem_.linear_lower;
  const Eigen::VectorXd& lin_hi = problem_.linear_upper;
  NeumaierSum sum;  // the linear block adds up to 10⁶ penalty terms per evaluation
  for (int i = 0; i < nn_; ++i) {
    const double s = rows_.scale(i);
    const double dv = s * (ev_.c(i) - clamp_to(ev_.c(i), rows_.lo(i), rows_.hi(i)));
    sum.add(0.5 * dv * dv);
    w_nl_(i) = dv * s;
  }
  if (!ev_.gradient(0.0, w_nl_, grad)) {
    grad.setConstant(kNaN);
    return kNaN;
  }
  if (m_ > 0) {
    linear_pass(*a_, xs, ev_.ax, grad, [&](Eigen::Index j, double value) {
      const double s = rows_.lin_scale(j);
      const double dv = s * (value - clamp_to(value, lin_lo(j), lin_hi(j)));
      if (dv == 0.0) return 0.0;
      sum.add(0.5 * dv * dv);
      return dv * s;
    });
    ev_.linear_done = true;
    if (!ev_.ax.allFinite()) {
      grad.setConstant(kNaN);
      return kNaN;
    }
  }
  return sum.value();
}

// The values at point xs (f and every row), including A x (when the last evaluation there did not
// compute it); no derivatives.
bool AugmentedLagrangian::evaluate_all(const Eigen::VectorXd& xs) {
  const bool ok = ev_.values_at(xs);
  if (m_ > 0 && !ev_.linear_done) {
    ev_.ax.noalias() = (*a_) * xs;
    ev_.linear_done = true;
  }
  return ok && ev_.ax.allFinite();
}

void AugmentedLagrangian::report_iteration(int outer, const LbfgsbResult& sub, const Measures& meas) const {
  if (!params_.on_outer_iteration) return;
  AlIterationInfo info;
  info.outer_iteration = outer;
  info.f = ev_.f;
  info.max_violation = meas.violation;
  info.stationarity = sub.projected_gradient_norm;
  info.complementarity = meas.complementarity;
  info.penalty = rho_;
  info.inner_status = sub.status;
  info.inner_iterations = sub.iterations;
  info.evaluations = ev_.count;
  params_.on_outer_iteration(info);
}

// From x_, whose violation `feas` stagnates, minimises the violation alone. True when that
// reaches a feasible point (x_ moves there); false when the problem reads as infeasible, with the
// result filled (at the least violation found, the last subproblem's multipliers).
bool AugmentedLagrangian::reach_least_violation(double feas, const Measures& meas, double stationarity) {
  // Relative to the violation: at a least-violation point J^T c vanishes while c does not, so
  // a tiny violation with a clear descent direction (|J^T c| ≫ tol |c|) is not stationary.
  // The tolerance is fixed for one L-BFGS-B run, so the run starts again from where it
  // stopped, relative to the violation there, as long as the violation keeps halving: a
  // problem whose violation fell tenfold in the first run is not shown infeasible by it (the
  // per-vertex top: 6.4e-4 to 6.6e-5 in 3 iterations, then feasible).
  const ObjectiveFunction violation_only = [this](const Eigen::VectorXd& xs, Eigen::VectorXd& grad) {
    return violation(xs, grad);
  };
  const double feas_tol = params_.feasibility_tolerance;
  Eigen::VectorXd least_x = x_;
  double least_feas = feas;
  Measures at_least = meas;
  double least_stationarity = stationarity;
  for (int restart = 0; restart < kMaxLeastViolationRestarts; ++restart) {
    LbfgsbOptions lv = params_.inner;
    lv.stop = params_.stop;
    lv.gradient_tolerance = params_.stationarity_tolerance * least_feas;
    lv.relative_gradient_tolerance = 0.0;
    lv.max_evaluations = std::max(1, std::min(lv.max_evaluations, params_.max_evaluations - ev_.count));
    const LbfgsbResult least = lbfgsb_minimize(violation_only, least_x, lower_, upper_, lv);
    evaluate_all(least.x);
    const Measures now = measures();
    const double now_feas = std::max(now.violation, now.scaled_violation);
    const bool halved = now_feas <= 0.5 * least_feas;
    if (now_feas <= least_feas) {
      least_x = least.x;
      at_least = now;
      least_stationarity = least.projected_gradient_norm;
    }
    least_feas = std::min(least_feas, now_feas);
    if (least_feas <= feas_tol || !halved || ev_.count >= params_.max_evaluations) break;
  }
  evaluate_all(least_x);
  if (least_feas > feas_tol) {
    // The multipliers stay those of the last subproblem; the violation is this point's.
    res_.stationarity = least_stationarity;
    fill_result(AlStatus::infeasible, at_least);
    return false;
  }
  x_ = least_x;
  return true;
}

AlResult AugmentedLagrangian::minimize() {
  if (!start()) {
    shift_.setZero();
    const Measures meas = measures();
    return fill_result(AlStatus::numerical_issue, meas);
  }
  choose_initial_penalty();
  const ObjectiveFunction subproblem_function = [this](const Eigen::VectorXd& xs, Eigen::VectorXd& grad) {
    return subproblem(xs, grad);
  };

  const double feas_tol = params_.feasibility_tolerance;
  double inner_tol = std::max(params_.initial_inner_tolerance, params_.stationarity_tolerance);
  double v_prev = kInf;
  double feas_prev = kInf;
  int stagnant = 0;
  int stalled = 0;
  Measures meas;
  LbfgsbOptions inner = params_.inner;
  inner.stop = params_.stop;
  const auto stop_requested = [this]() { return params_.stop && params_.stop->load(std::memory_order_relaxed); };
  bool hand_off_asked = false;

  for (int outer = 1; outer <= params_.max_outer_iterations; ++outer) {
    if (stop_requested()) {
      evaluate_all(x_);
      return fill_result(AlStatus::stopped, measures());
    }
    res_.outer_iterations = outer;
    for (Eigen::Index k = 0; k < nn_ + m_; ++k) {
      nu_bar_(k) = clamp_to(nu_(k), -params_.max_multiplier, params_.max_multiplier);
      shift_(k) = nu_bar_(k) / rho_;
    }
    const int budget = params_.max_evaluations - ev_.count;
    if (budget <= 0) return fill_result(AlStatus::max_evaluations, meas);
    inner.gradient_tolerance = inner_tol;
    inner.relative_gradient_tolerance = 0.0;
    inner.max_evaluations = std::min(inner.max_evaluations, budget);
    const LbfgsbResult sub = lbfgsb_minimize(subproblem_function, x_, lower_, upper_, inner);
    inner.max_evaluations = params_.inner.max_evaluations;
    res_.inner_iterations += sub.iterations;
    x_ = sub.x;
    evaluate_all(x_);
    meas = measures();
    nu_ = meas.nu;
    res_.stationarity = sub.projected_gradient_norm;
    report_iteration(outer, sub, meas);
    if (stop_requested()) return fill_result(AlStatus::stopped, meas);
    const double feas = std::max(meas.violation, meas.scaled_violation);
    if (feas <= feas_tol && sub.projected_gradient_norm <= params_.stationarity_tolerance &&
        meas.complementarity <= params_.complementarity_tolerance)
      return fill_result(AlStatus::converged, meas);
    if (ev_.count >= params_.max_evaluations) return fill_result(AlStatus::max_evaluations, meas);
    if (params_.hand_off && !hand_off_asked && feas <= params_.hand_off_violation) {
      hand_off_asked = true;
      if (params_.hand_off(x_)) return fill_result(AlStatus::handed_off, meas);
    }
    // The subproblem stopped at the budget this loop left it, not at its own cap. Its count
    // includes its start point, which the evaluator had cached and does not count again, so the
    // total can end just below the cap: every later subproblem would then stop at its start
    // point while the penalty kept growing, and the stagnation would read as infeasibility.
    if (sub.status == LbfgsbStatus::max_evaluations && budget <= params_.inner.max_evaluations)
      return fill_result(AlStatus::max_evaluations, meas);
    const bool inner_stuck = sub.status == LbfgsbStatus::small_reduction ||
                             sub.status == LbfgsbStatus::line_search_failed;
    if (feas <= feas_tol && meas.complementarity <= params_.complementarity_tolerance && inner_stuck) {
      if (++stalled >= params_.stall_patience) return fill_result(AlStatus::stalled, meas);
    } else {
      stalled = 0;
    }

    // Penalty update (ALGENCAN): keep ρ while V halves, else increase it.
    // Once V is within the feasibility tolerance a larger ρ only worsens the conditioning.
    if (meas.v > feas_tol && meas.v > params_.required_decrease * v_prev)
      rho_ = std::min(rho_ * params_.penalty_increase, params_.max_penalty);
    v_prev = meas.v;

    // Infeasibility: the violation stagnates although ρ keeps growing.
    if (feas > feas_tol && feas >= 0.99 * feas_prev) {
      // A subproblem that took no step (its gradient already below the inner tolerance) is no
      // evidence: the penalty grows and the next one moves.
      if (sub.iterations > 0) ++stagnant;
    } else {
      stagnant = 0;
    }
    feas_prev = feas;
    const bool clearly_infeasible = params_.clear_violation_factor > 0.0 && stagnant >= 1 &&
                                    feas > params_.clear_violation_factor * feas_tol;
    if (feas > feas_tol && (stagnant >= params_.infeasibility_patience || clearly_infeasible || rho_ >= params_.max_penalty)) {
      if (!reach_least_violation(feas, meas, sub.projected_gradient_norm)) return res_;
      // A feasible point exists: continue from it.
      stagnant = 0;
      feas_prev = kInf;
    }
    if (feas <= feas_tol) {
      inner_tol = params_.stationarity_tolerance;
    } else {
      inner_tol = std::max(params_.stationarity_tolerance,
                           std::min(params_.initial_inner_tolerance, params_.inner_tolerance_decrease * meas.v));
    }
  }
  evaluate_all(x_);
  meas = measures();
  return fill_result(AlStatus::max_outer_iterations, meas);
}

}  // namespace

AlResult augmented_lagrangian_minimize(const ConstrainedProblem& problem, const Eigen::VectorXd& x0, const AlOptions& params) {
  AlResult res;
  res.x = x0;  // the caller's point, unchanged, when the input is refused
  res.message = problem_error(problem, x0, params);
  if (!res.message.empty()) {
    res.status = AlStatus::invalid_input;
    return res;
  }
  return AugmentedLagrangian(problem, x0, params).minimize();
}

}  // namespace offsetopt
