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

// Evaluates f, ∇f and all nonlinear constraints with their Jacobian at one point (A x is added by
// linear_pass), and keeps the last point so the outer loop reads the values at the subproblem's
// solution for free.
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
        ji_(p.num_inequality, n) {}

  // Returns whether everything is finite at x.
  bool at(const Eigen::VectorXd& point) {
    if (valid_ && point.size() == x.size() && point == x) return finite;
    x = point;
    valid_ = true;
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

  int count = 0;
  Eigen::VectorXd x;
  double f = 0.0;
  bool finite = false;
  bool linear_done = false;  // ax holds A x for this x (written by linear_pass)
  Eigen::VectorXd grad;
  Eigen::VectorXd c;    // nonlinear rows: equalities then inequalities
  Eigen::MatrixXd jac;  // their Jacobian
  Eigen::VectorXd ax;   // linear rows, A x (valid when linear_done)

 private:
  const ConstrainedProblem& p_;
  int ne_, ni_;
  bool valid_ = false;
  Eigen::VectorXd ce_, ci_;
  Eigen::MatrixXd je_, ji_;
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
    case AlStatus::numerical_issue: return "numerical-issue";
    case AlStatus::invalid_input: return "invalid-input";
  }
  return "unknown";
}

AlResult augmented_lagrangian_minimize(const ConstrainedProblem& problem,
                                       const Eigen::VectorXd& x0, const AlOptions& params) {
  AlResult res;
  res.x = x0;
  const int n = problem.num_variables;
  const int ne = problem.num_equality;
  const int ni = problem.num_inequality;
  const int nn = ne + ni;
  const Eigen::MatrixXd* a = problem.linear_matrix;
  const Eigen::Index m = a ? a->rows() : 0;

  // ---- Validation (once) ----
  std::string& msg = res.message;
  msg = params.check();
  if (msg.empty() && n < 1) msg = "num_variables must be >= 1";
  if (msg.empty() && x0.size() != n) msg = "start point has the wrong length";
  if (msg.empty() && !x0.allFinite()) msg = "start point not finite";
  if (msg.empty() && !problem.objective) msg = "no objective function";
  if (msg.empty() && (ne < 0 || ni < 0)) msg = "negative constraint count";
  if (msg.empty() && ne > 0 && !problem.equality) msg = "num_equality > 0 without a function";
  if (msg.empty() && ni > 0 && !problem.inequality) msg = "num_inequality > 0 without a function";
  if (msg.empty() && ((problem.lower.size() != 0 && problem.lower.size() != n) ||
                      (problem.upper.size() != 0 && problem.upper.size() != n)))
    msg = "bounds must be empty or of length num_variables";
  if (msg.empty() && a && a->cols() != n) msg = "linear_matrix must have num_variables columns";
  if (msg.empty() && (problem.linear_lower.size() != m || problem.linear_upper.size() != m))
    msg = "linear bounds must have one entry per row of linear_matrix";
  if (msg.empty() && a && !a->allFinite()) msg = "linear_matrix not finite";
  const Eigen::VectorXd lower =
      problem.lower.size() ? problem.lower : Eigen::VectorXd::Constant(n, -kInf);
  const Eigen::VectorXd upper =
      problem.upper.size() ? problem.upper : Eigen::VectorXd::Constant(n, kInf);
  for (int i = 0; msg.empty() && i < n; ++i) {
    if (std::isnan(lower(i)) || std::isnan(upper(i)) || lower(i) > upper(i) ||
        lower(i) == kInf || upper(i) == -kInf)
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
  if (!msg.empty()) {
    res.status = AlStatus::invalid_input;
    res.x = x0;  // the caller's point, unchanged
    return res;
  }

  Rows rows;
  rows.lo.resize(nn);
  rows.hi.resize(nn);
  for (int i = 0; i < nn; ++i) {
    rows.lo(i) = i < ne ? 0.0 : -kInf;
    rows.hi(i) = 0.0;
  }

  Eigen::VectorXd x = x0;
  for (int i = 0; i < n; ++i) x(i) = clamp_to(x(i), lower(i), upper(i));
  Evaluator ev(problem, n, static_cast<int>(m));
  bool start_finite = ev.at(x);
  if (m > 0) {
    ev.ax.noalias() = (*a) * x;
    ev.linear_done = true;
    start_finite = start_finite && ev.ax.allFinite();
  }

  // ---- Scaling from the start point ----
  auto scale_of = [&](double gradient_norm) {
    if (params.scale_floor == 0.0) return 1.0;
    return 1.0 / std::max(params.scale_floor, gradient_norm);
  };
  const double sf = start_finite ? scale_of(ev.grad.lpNorm<Eigen::Infinity>()) : 1.0;
  rows.scale.resize(nn);
  for (int i = 0; i < nn; ++i)
    rows.scale(i) = start_finite ? scale_of(ev.jac.row(i).lpNorm<Eigen::Infinity>()) : 1.0;
  rows.lin_scale.resize(m);
  for (Eigen::Index j = 0; j < m; ++j) rows.lin_scale(j) = scale_of(a->row(j).lpNorm<Eigen::Infinity>());

  const Eigen::VectorXd& lin_lo = problem.linear_lower;
  const Eigen::VectorXd& lin_hi = problem.linear_upper;

  // Multipliers (scaled), nonlinear rows then linear rows; penalty.
  Eigen::VectorXd nu_bar = Eigen::VectorXd::Zero(nn + m);
  Eigen::VectorXd nu = nu_bar;
  // A warm start converts the unscaled multipliers (see fill_result); inequality ones are >= 0.
  for (int i = 0; i < nn; ++i) {
    const bool eq = i < ne;
    const Eigen::VectorXd& given = eq ? params.initial_equality_multipliers : params.initial_inequality_multipliers;
    if (given.size() == 0) continue;
    const double unscaled = given(eq ? i : i - ne);
    nu(i) = (eq ? unscaled : std::max(0.0, unscaled)) * sf / rows.scale(i);
  }
  Eigen::VectorXd shift = Eigen::VectorXd::Zero(nn + m);  // nu_bar / rho
  Eigen::VectorXd w_nl(nn);
  double rho = 1.0;

  auto measures = [&]() {
    Measures out;
    out.nu.resize(nn + m);
    auto row = [&](Eigen::Index k, double value, double lo, double hi, double s) {
      const double viol = value < lo ? lo - value : (value > hi ? value - hi : 0.0);
      out.violation = std::max(out.violation, viol);
      out.scaled_violation = std::max(out.scaled_violation, s * viol);
      const double sc = s * value, slo = s * lo, shi = s * hi;
      const double t = sc + shift(k);
      const double pt = clamp_to(t, slo, shi);
      out.v = std::max(out.v, std::fabs(sc - pt));
      const double nu_k = rho * (t - pt);
      out.nu(k) = nu_k;
      double gap = 0.0;
      if (nu_k > 0.0) gap = std::fabs(shi - sc);
      if (nu_k < 0.0) gap = std::fabs(sc - slo);
      out.complementarity = std::max(out.complementarity, std::min(std::fabs(nu_k), gap));
    };
    for (int i = 0; i < nn; ++i) row(i, ev.c(i), rows.lo(i), rows.hi(i), rows.scale(i));
    for (Eigen::Index j = 0; j < m; ++j)
      row(nn + j, ev.ax(j), lin_lo(j), lin_hi(j), rows.lin_scale(j));
    return out;
  };

  auto fill_result = [&](AlStatus status, const Measures& meas) {
    res.status = status;
    res.x = ev.x;
    res.f = ev.f;
    res.max_violation = meas.violation;
    res.scaled_violation = meas.scaled_violation;
    res.complementarity = meas.complementarity;
    res.penalty = rho;
    res.evaluations = ev.count;
    res.equality_multipliers.resize(ne);
    res.inequality_multipliers.resize(ni);
    res.linear_multipliers.resize(m);
    for (int i = 0; i < nn; ++i) {
      const double unscaled = nu(i) * rows.scale(i) / sf;
      if (i < ne) {
        res.equality_multipliers(i) = unscaled;
      } else {
        res.inequality_multipliers(i - ne) = unscaled;
      }
    }
    for (Eigen::Index j = 0; j < m; ++j) res.linear_multipliers(j) = nu(nn + j) * rows.lin_scale(j) / sf;
    res.equality_values = ev.c.head(ne);
    res.inequality_values = ev.c.tail(ni);
    return res;
  };

  if (!start_finite) {
    shift.setZero();
    const Measures meas = measures();
    return fill_result(AlStatus::numerical_issue, meas);
  }

  if (params.initial_penalty > 0.0) {
    rho = params.initial_penalty;
  } else {
    double half_sq = 0.0;
    auto add_sq = [&](double value, double lo, double hi, double s) {
      const double viol = value < lo ? lo - value : (value > hi ? value - hi : 0.0);
      half_sq += 0.5 * (s * viol) * (s * viol);
    };
    for (int i = 0; i < nn; ++i) add_sq(ev.c(i), rows.lo(i), rows.hi(i), rows.scale(i));
    for (Eigen::Index j = 0; j < m; ++j) add_sq(ev.ax(j), lin_lo(j), lin_hi(j), rows.lin_scale(j));
    rho = clamp_to(10.0 * std::max(1.0, std::fabs(sf * ev.f)) / std::max(1.0, half_sq), 1e-8, 1e8);
  }
  rho = std::min(rho, params.max_penalty);

  // The subproblem: scaled augmented Lagrangian over the box.
  ObjectiveFunction subproblem = [&](const Eigen::VectorXd& xs, Eigen::VectorXd& grad) -> double {
    if (!ev.at(xs)) {
      grad.setConstant(kNaN);
      return kNaN;
    }
    grad = sf * ev.grad;
    NeumaierSum sum;  // the linear block adds up to 10⁶ penalty terms per evaluation
    sum.add(sf * ev.f);
    for (int i = 0; i < nn; ++i) {
      const double s = rows.scale(i);
      const double t = s * ev.c(i) + shift(i);
      const double dv = t - clamp_to(t, s * rows.lo(i), s * rows.hi(i));
      sum.add(0.5 * rho * dv * dv);
      w_nl(i) = rho * dv * s;
    }
    if (nn > 0) grad.noalias() += ev.jac.transpose() * w_nl;
    if (m > 0) {
      linear_pass(*a, xs, ev.ax, grad, [&](Eigen::Index j, double value) {
        const double s = rows.lin_scale(j);
        const double t = s * value + shift(nn + j);
        const double dv = t - clamp_to(t, s * lin_lo(j), s * lin_hi(j));
        if (dv == 0.0) return 0.0;
        sum.add(0.5 * rho * dv * dv);
        return rho * dv * s;
      });
      ev.linear_done = true;
      if (!ev.ax.allFinite()) {
        grad.setConstant(kNaN);
        return kNaN;
      }
    }
    return sum.value();
  };

  // ½ Σ (s_i dist(c_i, [lo_i, hi_i]))²: minimised over the box to find a least-violation point.
  ObjectiveFunction violation = [&](const Eigen::VectorXd& xs, Eigen::VectorXd& grad) -> double {
    if (!ev.at(xs)) {
      grad.setConstant(kNaN);
      return kNaN;
    }
    grad.setZero();
    NeumaierSum sum;  // the linear block adds up to 10⁶ penalty terms per evaluation
    for (int i = 0; i < nn; ++i) {
      const double s = rows.scale(i);
      const double dv = s * (ev.c(i) - clamp_to(ev.c(i), rows.lo(i), rows.hi(i)));
      sum.add(0.5 * dv * dv);
      w_nl(i) = dv * s;
    }
    if (nn > 0) grad.noalias() += ev.jac.transpose() * w_nl;
    if (m > 0) {
      linear_pass(*a, xs, ev.ax, grad, [&](Eigen::Index j, double value) {
        const double s = rows.lin_scale(j);
        const double dv = s * (value - clamp_to(value, lin_lo(j), lin_hi(j)));
        if (dv == 0.0) return 0.0;
        sum.add(0.5 * dv * dv);
        return dv * s;
      });
      ev.linear_done = true;
      if (!ev.ax.allFinite()) {
        grad.setConstant(kNaN);
        return kNaN;
      }
    }
    return sum.value();
  };

  // Everything at point xs, including A x (when the last evaluation there did not compute it).
  auto evaluate_all = [&](const Eigen::VectorXd& xs) {
    const bool ok = ev.at(xs);
    if (m > 0 && !ev.linear_done) {
      ev.ax.noalias() = (*a) * xs;
      ev.linear_done = true;
    }
    return ok && ev.ax.allFinite();
  };

  const double feas_tol = params.feasibility_tolerance;
  double inner_tol = std::max(params.initial_inner_tolerance, params.stationarity_tolerance);
  double v_prev = kInf;
  double feas_prev = kInf;
  int stagnant = 0;
  int stalled = 0;
  Measures meas;
  LbfgsbOptions inner = params.inner;

  for (int outer = 1; outer <= params.max_outer_iterations; ++outer) {
    res.outer_iterations = outer;
    for (Eigen::Index k = 0; k < nn + m; ++k) {
      nu_bar(k) = clamp_to(nu(k), -params.max_multiplier, params.max_multiplier);
      shift(k) = nu_bar(k) / rho;
    }
    const int budget = params.max_evaluations - ev.count;
    if (budget <= 0) return fill_result(AlStatus::max_evaluations, meas);
    inner.gradient_tolerance = inner_tol;
    inner.relative_gradient_tolerance = 0.0;
    inner.max_evaluations = std::min(inner.max_evaluations, budget);
    const LbfgsbResult sub = lbfgsb_minimize(subproblem, x, lower, upper, inner);
    inner.max_evaluations = params.inner.max_evaluations;
    res.inner_iterations += sub.iterations;
    x = sub.x;
    evaluate_all(x);
    meas = measures();
    nu = meas.nu;
    res.stationarity = sub.projected_gradient_norm;
    if (params.on_outer_iteration) {
      AlIterationInfo info;
      info.outer_iteration = outer;
      info.f = ev.f;
      info.max_violation = meas.violation;
      info.stationarity = sub.projected_gradient_norm;
      info.complementarity = meas.complementarity;
      info.penalty = rho;
      info.inner_status = sub.status;
      info.inner_iterations = sub.iterations;
      info.evaluations = ev.count;
      params.on_outer_iteration(info);
    }
    const double feas = std::max(meas.violation, meas.scaled_violation);
    if (feas <= feas_tol && sub.projected_gradient_norm <= params.stationarity_tolerance &&
        meas.complementarity <= params.complementarity_tolerance)
      return fill_result(AlStatus::converged, meas);
    if (ev.count >= params.max_evaluations) return fill_result(AlStatus::max_evaluations, meas);
    // The subproblem stopped at the budget this loop left it, not at its own cap. Its count
    // includes its start point, which the evaluator had cached and does not count again, so the
    // total can end just below the cap: every later subproblem would then stop at its start
    // point while the penalty kept growing, and the stagnation would read as infeasibility.
    if (sub.status == LbfgsbStatus::max_evaluations && budget <= params.inner.max_evaluations)
      return fill_result(AlStatus::max_evaluations, meas);
    const bool inner_stuck = sub.status == LbfgsbStatus::small_reduction ||
                             sub.status == LbfgsbStatus::line_search_failed;
    if (feas <= feas_tol && meas.complementarity <= params.complementarity_tolerance && inner_stuck) {
      if (++stalled >= params.stall_patience) return fill_result(AlStatus::stalled, meas);
    } else {
      stalled = 0;
    }

    // Penalty update (ALGENCAN): keep ρ while V halves, else increase it.
    // Once V is within the feasibility tolerance a larger ρ only worsens the conditioning.
    if (meas.v > feas_tol && meas.v > params.required_decrease * v_prev)
      rho = std::min(rho * params.penalty_increase, params.max_penalty);
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
    const bool clearly_infeasible = params.clear_violation_factor > 0.0 && stagnant >= 1 &&
                                    feas > params.clear_violation_factor * feas_tol;
    if (feas > feas_tol && (stagnant >= params.infeasibility_patience || clearly_infeasible || rho >= params.max_penalty)) {
      // Relative to the violation: at a least-violation point J^T c vanishes while c does not, so
      // a tiny violation with a clear descent direction (|J^T c| ≫ tol |c|) is not stationary.
      // The tolerance is fixed for one L-BFGS-B run, so the run starts again from where it
      // stopped, relative to the violation there, as long as the violation keeps halving: a
      // problem whose violation fell tenfold in the first run is not shown infeasible by it (the
      // per-vertex top: 6.4e-4 to 6.6e-5 in 3 iterations, then feasible).
      Eigen::VectorXd least_x = x;
      double least_feas = feas;
      Measures at_least = meas;
      double least_stationarity = sub.projected_gradient_norm;
      for (int restart = 0; restart < kMaxLeastViolationRestarts; ++restart) {
        LbfgsbOptions lv = params.inner;
        lv.gradient_tolerance = params.stationarity_tolerance * least_feas;
        lv.relative_gradient_tolerance = 0.0;
        lv.max_evaluations = std::max(1, std::min(lv.max_evaluations, params.max_evaluations - ev.count));
        const LbfgsbResult least = lbfgsb_minimize(violation, least_x, lower, upper, lv);
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
        if (least_feas <= feas_tol || !halved || ev.count >= params.max_evaluations) break;
      }
      evaluate_all(least_x);
      if (least_feas > feas_tol) {
        // The multipliers stay those of the last subproblem; the violation is this point's.
        res.stationarity = least_stationarity;
        return fill_result(AlStatus::infeasible, at_least);
      }
      // A feasible point exists: continue from it.
      x = least_x;
      stagnant = 0;
      feas_prev = kInf;
    }
    if (feas <= feas_tol) {
      inner_tol = params.stationarity_tolerance;
    } else {
      inner_tol = std::max(params.stationarity_tolerance,
                           std::min(params.initial_inner_tolerance, params.inner_tolerance_decrease * meas.v));
    }
  }
  evaluate_all(x);
  meas = measures();
  return fill_result(AlStatus::max_outer_iterations, meas);
}

}  // namespace offsetopt
