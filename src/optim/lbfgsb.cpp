#include "optim/lbfgsb.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "optim/cauchy_point.h"
#include "optim/lbfgs_memory.h"
#include "optim/more_thuente.h"
#include "optim/subspace_minimization.h"

namespace offsetopt {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kBigStep = 1e10;  // step cap along directions no bound can block (Fortran)

void clamp_into(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, Eigen::VectorXd& v) {
  for (Eigen::Index i = 0; i < v.size(); ++i) v(i) = std::min(upper(i), std::max(lower(i), v(i)));
}

bool finite_value_and_gradient(double f, const Eigen::VectorXd& g) {
  return std::isfinite(f) && g.allFinite();
}

// Largest step along d from x that stays in the box (at least 1, because x + d is feasible).
double max_feasible_step(const Eigen::VectorXd& x, const Eigen::VectorXd& d,
                         const Eigen::VectorXd& lower, const Eigen::VectorXd& upper) {
  double step = kBigStep;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    if (d(i) < 0.0 && std::isfinite(lower(i))) {
      const double room = lower(i) - x(i);
      if (room >= 0.0) {
        step = 0.0;
      } else if (d(i) * step < room) {
        step = room / d(i);
      }
    } else if (d(i) > 0.0 && std::isfinite(upper(i))) {
      const double room = upper(i) - x(i);
      if (room <= 0.0) {
        step = 0.0;
      } else if (d(i) * step > room) {
        step = room / d(i);
      }
    }
  }
  return std::max(step, 1.0);
}

// What is wrong with the problem or the options; empty when usable.
std::string input_error(const ObjectiveFunction& f, const Eigen::VectorXd& x0, const Eigen::VectorXd& lower_in,
                        const Eigen::VectorXd& upper_in, const LbfgsbOptions& params) {
  const Eigen::Index n = x0.size();
  std::string message = params.check();
  if (message.empty() && n == 0) message = "no variables";
  if (message.empty() && !f) message = "no objective function";
  if (message.empty() && ((lower_in.size() != 0 && lower_in.size() != n) || (upper_in.size() != 0 && upper_in.size() != n)))
    message = "bounds must be empty or of the length of x";
  if (message.empty() && !x0.allFinite()) message = "start point not finite";
  if (!message.empty()) return message;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double lo = lower_in.size() ? lower_in(i) : -kInf, hi = upper_in.size() ? upper_in(i) : kInf;
    if (std::isnan(lo) || std::isnan(hi) || lo > hi || lo == kInf || hi == -kInf)
      return "bounds of variable " + std::to_string(i) + " are empty or NaN";
  }
  return message;
}

// Where the subspace minimisation starts: the generalized Cauchy point, or, without any bound
// once the memory holds a pair (Fortran), x itself with every variable free (the step is then
// plain L-BFGS).
CauchyPoint cauchy_start(const Eigen::VectorXd& x, const Eigen::VectorXd& g, const Eigen::VectorXd& lower,
                         const Eigen::VectorXd& upper, const LbfgsMemory& memory, bool has_bounds) {
  if (has_bounds || memory.size() == 0) return generalized_cauchy_point(x, g, lower, upper, memory);
  CauchyPoint cauchy;
  cauchy.x = x;
  cauchy.c = Eigen::VectorXd::Zero(2 * memory.size());
  cauchy.free.resize(static_cast<size_t>(x.size()));
  for (Eigen::Index i = 0; i < x.size(); ++i) cauchy.free[static_cast<size_t>(i)] = static_cast<int>(i);
  return cauchy;
}

// Trial points of one line search and the lowest one with sufficient decrease (kept between
// searches so the vectors are allocated once).
struct LineSearchPoints {
  Eigen::VectorXd xt, gt, best_x, best_g;
};

struct LineSearchOutcome {
  bool accepted = false;          // points.xt, points.gt hold the accepted point
  bool evaluation_limit = false;  // stopped at params.max_evaluations
  double f = 0.0;                 // at the accepted point
};

// The Moré-Thuente search from x (value fx, slope gd < 0 along d) towards x_bar = x + d, first
// trial step `stp`, steps at most ls.stpmax; each trial point is clamped into the box.
// Accepts a strong Wolfe point, or an approximate Wolfe point where f is flat to rounding, or
// else the lowest trial point with sufficient decrease.
LineSearchOutcome search_line(const ObjectiveFunction& f, const Eigen::VectorXd& x, double fx, double gd,
                              const Eigen::VectorXd& d, const Eigen::VectorXd& x_bar, const Eigen::VectorXd& lower,
                              const Eigen::VectorXd& upper, double stp, MoreThuenteOptions ls,
                              const LbfgsbOptions& params, int& evaluations, LineSearchPoints& points) {
  Eigen::VectorXd& xt = points.xt;
  Eigen::VectorXd& gt = points.gt;
  LineSearchOutcome out;
  MoreThuenteSearch search;
  MoreThuenteStatus state = search.start(fx, gd, stp, ls);
  bool have_best = false;
  double best_f = 0.0;
  int ls_evaluations = 0;
  while (state == MoreThuenteStatus::evaluate) {
    if (ls_evaluations >= params.max_line_search_evaluations) break;
    if (evaluations >= params.max_evaluations) {
      out.evaluation_limit = true;
      break;
    }
    stp = search.step();
    if (stp == 1.0) {
      xt = x_bar;  // exactly the subspace point: no rounding off a bound
    } else {
      xt = x + stp * d;
      clamp_into(lower, upper, xt);
    }
    const double ft = f(xt, gt);
    ++evaluations;
    ++ls_evaluations;
    if (!finite_value_and_gradient(ft, gt)) {
      // Undefined there: restart the search on the half step and never go beyond it again.
      ls.stpmax = 0.5 * stp;
      state = search.start(fx, gd, ls.stpmax, ls);
      continue;
    }
    const bool sufficient = ft <= fx + params.wolfe_decrease * stp * gd;
    if (sufficient && (!have_best || ft < best_f)) {
      have_best = true;
      best_f = ft;
      points.best_x = xt;
      points.best_g = gt;
    }
    const double gdt = gt.dot(d);
    state = search.advance(ft, gdt);
    if (state == MoreThuenteStatus::converged) {
      out.accepted = true;
      out.f = ft;
    } else if (!sufficient && ft <= fx + params.function_noise * std::fabs(fx) &&
               (2.0 * params.wolfe_decrease - 1.0) * gd >= gdt && gdt >= params.wolfe_curvature * gd) {
      out.accepted = true;  // approximate Wolfe: f is flat to rounding, the slope has turned
      out.f = ft;
      break;
    }
  }
  if (!out.accepted && have_best) {
    // Warnings, the per-search cap or the evaluation cap: fall back on the lowest point with
    // sufficient decrease, so every accepted step still decreases f.
    out.accepted = true;
    xt = points.best_x;
    gt = points.best_g;
    out.f = best_f;
  }
  return out;
}

}  // namespace

std::string LbfgsbOptions::check() const {
  if (memory < 1 || memory > 100) return "memory must be in [1, 100]";
  if (!(gradient_tolerance >= 0.0) || !std::isfinite(gradient_tolerance))
    return "gradient_tolerance must be finite and >= 0";
  if (!(relative_gradient_tolerance >= 0.0) || !std::isfinite(relative_gradient_tolerance))
    return "relative_gradient_tolerance must be finite and >= 0";
  if (gradient_tolerance == 0.0 && relative_gradient_tolerance == 0.0)
    return "gradient_tolerance and relative_gradient_tolerance cannot both be 0";
  if (!(function_tolerance >= 0.0) || !std::isfinite(function_tolerance))
    return "function_tolerance must be finite and >= 0";
  if (max_iterations < 1) return "max_iterations must be >= 1";
  if (max_evaluations < 1) return "max_evaluations must be >= 1";
  if (!(wolfe_decrease > 0.0) || !(wolfe_decrease < wolfe_curvature) ||
      !(wolfe_curvature < 1.0))
    return "need 0 < wolfe_decrease < wolfe_curvature < 1";
  if (!(line_search_xtol >= 0.0) || !(line_search_xtol < 1.0))
    return "line_search_xtol must be in [0, 1)";
  if (max_line_search_evaluations < 1) return "max_line_search_evaluations must be >= 1";
  if (!(function_noise >= 0.0) || !(function_noise < 1.0))
    return "function_noise must be in [0, 1)";
  if (max_noise_steps < 1) return "max_noise_steps must be >= 1";
  return std::string();
}

const char* to_string(LbfgsbStatus status) {
  switch (status) {
    case LbfgsbStatus::converged: return "converged";
    case LbfgsbStatus::small_reduction: return "small-reduction";
    case LbfgsbStatus::max_iterations: return "max-iterations";
    case LbfgsbStatus::max_evaluations: return "max-evaluations";
    case LbfgsbStatus::line_search_failed: return "line-search-failed";
    case LbfgsbStatus::stopped: return "stopped";
    case LbfgsbStatus::numerical_issue: return "numerical-issue";
    case LbfgsbStatus::invalid_input: return "invalid-input";
  }
  return "unknown";
}

double projected_gradient_norm(const Eigen::VectorXd& x, const Eigen::VectorXd& g,
                               const Eigen::VectorXd& lower, const Eigen::VectorXd& upper) {
  double norm = 0.0;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    double gi = g(i);
    if (gi < 0.0) {
      if (std::isfinite(upper(i))) gi = std::max(x(i) - upper(i), gi);
    } else {
      if (std::isfinite(lower(i))) gi = std::min(x(i) - lower(i), gi);
    }
    norm = std::max(norm, std::fabs(gi));
  }
  return norm;
}

LbfgsbResult lbfgsb_minimize(const ObjectiveFunction& f, const Eigen::VectorXd& x0,
                             const Eigen::VectorXd& lower_in, const Eigen::VectorXd& upper_in,
                             const LbfgsbOptions& params) {
  LbfgsbResult res;
  res.x = x0;
  const Eigen::Index n = x0.size();
  res.message = input_error(f, x0, lower_in, upper_in, params);
  if (!res.message.empty()) {
    res.status = LbfgsbStatus::invalid_input;
    return res;
  }
  const Eigen::VectorXd lower = lower_in.size() ? lower_in : Eigen::VectorXd::Constant(n, -kInf);
  const Eigen::VectorXd upper = upper_in.size() ? upper_in : Eigen::VectorXd::Constant(n, kInf);

  bool has_bounds = false;
  bool boxed = true;
  for (Eigen::Index i = 0; i < n; ++i) {
    const bool lo = std::isfinite(lower(i));
    const bool hi = std::isfinite(upper(i));
    has_bounds = has_bounds || lo || hi;
    boxed = boxed && lo && hi;
  }

  Eigen::VectorXd x = x0;
  clamp_into(lower, upper, x);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(n);
  double fx = f(x, g);
  int evaluations = 1;
  int iterations = 0;
  int resets = 0;
  double pg = projected_gradient_norm(x, g, lower, upper);

  // The lowest f seen at an iterate: noise-level steps may raise f by a rounding error.
  Eigen::VectorXd lowest_x = x, lowest_g = g;
  double lowest_f = fx, lowest_pg = pg;
  auto finish = [&](LbfgsbStatus status) {
    res.status = status;
    if (status != LbfgsbStatus::converged && lowest_f < fx) {
      x = lowest_x;
      g = lowest_g;
      fx = lowest_f;
      pg = lowest_pg;
    }
    res.x = x;
    res.f = fx;
    res.grad = g;
    res.projected_gradient_norm = pg;
    res.iterations = iterations;
    res.evaluations = evaluations;
    res.memory_resets = resets;
    return res;
  };

  if (!finite_value_and_gradient(fx, g)) return finish(LbfgsbStatus::numerical_issue);
  const double tolerance =
      std::max(params.gradient_tolerance, params.relative_gradient_tolerance * pg);
  if (pg <= tolerance) return finish(LbfgsbStatus::converged);

  LbfgsMemory memory(static_cast<int>(n), params.memory);
  MoreThuenteOptions ls;
  ls.ftol = params.wolfe_decrease;
  ls.gtol = params.wolfe_curvature;
  ls.xtol = params.line_search_xtol;
  ls.stpmin = 0.0;

  LineSearchPoints points{Eigen::VectorXd(n), Eigen::VectorXd(n), Eigen::VectorXd(n), Eigen::VectorXd(n)};
  Eigen::VectorXd d(n);
  int noise_steps = 0;
  double smallest_pg = pg;

  for (;;) {
    if (iterations >= params.max_iterations) return finish(LbfgsbStatus::max_iterations);
    if (evaluations >= params.max_evaluations) return finish(LbfgsbStatus::max_evaluations);
    if (params.stop && params.stop->load(std::memory_order_relaxed)) return finish(LbfgsbStatus::stopped);

    // Search direction: Cauchy point, then subspace minimisation.
    const CauchyPoint cauchy = cauchy_start(x, g, lower, upper, memory, has_bounds);
    const SubspaceStep sub = subspace_minimization(x, g, lower, upper, memory, cauchy);
    if (!sub.ok) {
      memory.reset();
      ++resets;
      continue;
    }
    d = sub.x_bar - x;
    const double gd = g.dot(d);
    if (!(gd < 0.0)) {
      if (memory.size() > 0) {
        memory.reset();
        ++resets;
        continue;
      }
      return finish(LbfgsbStatus::line_search_failed);
    }

    // Line search along d, steps limited to the box.
    double stpmax = kBigStep;
    if (has_bounds) stpmax = iterations == 0 ? 1.0 : max_feasible_step(x, d, lower, upper);
    double stp = 1.0;
    if (iterations == 0 && !boxed) stp = std::min(1.0 / d.norm(), stpmax);
    ls.stpmax = stpmax;
    const LineSearchOutcome step = search_line(f, x, fx, gd, d, sub.x_bar, lower, upper, stp, ls, params, evaluations, points);
    const bool evaluation_limit = step.evaluation_limit;
    if (!step.accepted) {
      if (evaluation_limit) return finish(LbfgsbStatus::max_evaluations);
      if (memory.size() > 0) {
        memory.reset();
        ++resets;
        continue;
      }
      return finish(LbfgsbStatus::line_search_failed);
    }

    const Eigen::VectorXd s = points.xt - x;
    const Eigen::VectorXd y = points.gt - g;
    const double slope = -g.dot(s);
    const double f_old = fx;
    x = points.xt;
    g = points.gt;
    fx = step.f;
    ++iterations;
    pg = projected_gradient_norm(x, g, lower, upper);
    const bool new_low_pg = pg < smallest_pg;
    smallest_pg = std::min(smallest_pg, pg);
    if (fx < lowest_f) {
      lowest_f = fx;
      lowest_x = x;
      lowest_g = g;
      lowest_pg = pg;
    }
    if (pg <= tolerance) return finish(LbfgsbStatus::converged);
    if (f_old - fx <= 0.0) {
      // No decrease of f: still progress while the projected gradient reaches new lows.
      if (new_low_pg) {
        noise_steps = 0;
      } else if (++noise_steps >= params.max_noise_steps) {
        return finish(LbfgsbStatus::small_reduction);
      }
    } else {
      noise_steps = 0;
      if (f_old - fx <= params.function_tolerance * std::max(std::fabs(f_old), std::fabs(fx)))
        return finish(LbfgsbStatus::small_reduction);
    }
    if (evaluation_limit) return finish(LbfgsbStatus::max_evaluations);
    if (s.dot(y) > kEps * slope) {
      if (!memory.add(s, y)) ++resets;
    }
  }
}

}  // namespace offsetopt
