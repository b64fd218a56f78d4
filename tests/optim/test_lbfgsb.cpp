// L-BFGS-B against known minima: Rosenbrock (chained, n = 2, 10, 100), bounded Rosenbrock pairs
// with known constrained minimisers, random bounded convex quadratics against a brute-force
// enumeration of all active sets, and a constructed n = 100 bounded quadratic.
#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "optim/lbfgsb.h"
#include "util/rng.h"

using namespace offsetopt;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Chained Rosenbrock: Σ_{i<n-1} 100 (x_{i+1} − x_i²)² + (1 − x_i)²; minimum 0 at (1, …, 1).
double chained_rosenbrock(const VectorXd& x, VectorXd& g) {
  const Eigen::Index n = x.size();
  double f = 0.0;
  g.setZero();
  for (Eigen::Index i = 0; i + 1 < n; ++i) {
    const double a = x(i + 1) - x(i) * x(i);
    const double b = 1.0 - x(i);
    f += 100.0 * a * a + b * b;
    g(i) += -400.0 * a * x(i) - 2.0 * b;
    g(i + 1) += 200.0 * a;
  }
  return f;
}

// Separable (extended) Rosenbrock in pairs (x_{2j}, x_{2j+1}).
double pair_rosenbrock(const VectorXd& x, VectorXd& g) {
  double f = 0.0;
  g.setZero();
  for (Eigen::Index j = 0; j + 1 < x.size(); j += 2) {
    const double a = x(j + 1) - x(j) * x(j);
    const double b = 1.0 - x(j);
    f += 100.0 * a * a + b * b;
    g(j) = -400.0 * a * x(j) - 2.0 * b;
    g(j + 1) = 200.0 * a;
  }
  return f;
}

VectorXd rosenbrock_start(int n) {
  VectorXd x(n);
  for (int i = 0; i < n; ++i) x(i) = (i % 2 == 0) ? -1.2 : 1.0;
  return x;
}

}  // namespace

TEST_CASE("lbfgsb: unconstrained chained Rosenbrock reaches (1,...,1) for n = 2, 10, 100") {
  for (int n : {2, 10, 100}) {
    CAPTURE(n);
    LbfgsbOptions params;
    params.gradient_tolerance = 1e-10;
    params.function_tolerance = 0.0;
    const LbfgsbResult r = lbfgsb_minimize(chained_rosenbrock, rosenbrock_start(n), VectorXd(),
                                           VectorXd(), params);
    MESSAGE("n=" << n << " status=" << std::string(to_string(r.status)) << " it=" << r.iterations
                 << " ev=" << r.evaluations << " f=" << r.f << " pg=" << r.projected_gradient_norm);
    CHECK(r.status == LbfgsbStatus::converged);
    CHECK((r.x.array() - 1.0).abs().maxCoeff() < 1e-7);
    CHECK(r.f < 1e-15);
  }
}

TEST_CASE("lbfgsb: bounded Rosenbrock pairs stop on the bounds with the known minimisers") {
  // Pair j of the separable Rosenbrock function gets bound b_j on its first variable:
  //   x_{2j} ≤ b < 1   → minimiser (b, b²), f = (1 − b)²   (f ≥ (1 − x)² ≥ (1 − b)²)
  //   x_{2j} ≥ b > 1   → minimiser (b, b²), f = (b − 1)²
  //   unbounded        → (1, 1), f = 0
  for (int n : {10, 100}) {
    CAPTURE(n);
    VectorXd lower = VectorXd::Constant(n, -kInf), upper = VectorXd::Constant(n, kInf);
    VectorXd expected(n);
    std::vector<int> active;
    double f_star = 0.0;
    for (int j = 0; j < n; j += 2) {
      double b = 1.0;
      switch ((j / 2) % 3) {
        case 0: b = 0.5 - 0.01 * j; upper(j) = b; active.push_back(j); break;
        case 1: b = 1.5 + 0.01 * j; lower(j) = b; active.push_back(j); break;
        default: break;
      }
      expected(j) = b;
      expected(j + 1) = b * b;
      f_star += (1.0 - b) * (1.0 - b);
    }
    LbfgsbOptions params;
    params.gradient_tolerance = 1e-10;
    params.function_tolerance = 0.0;
    const LbfgsbResult r = lbfgsb_minimize(pair_rosenbrock, rosenbrock_start(n), lower, upper, params);
    MESSAGE("n=" << n << " status=" << std::string(to_string(r.status)) << " it=" << r.iterations
                 << " ev=" << r.evaluations);
    CHECK(r.status == LbfgsbStatus::converged);
    CHECK((r.x - expected).lpNorm<Eigen::Infinity>() < 1e-7);
    CHECK(std::fabs(r.f - f_star) < 1e-10 * std::max(1.0, f_star));
    // Active set: exactly the bounded variables sit exactly on their bound; nothing else does.
    for (int i = 0; i < n; ++i) {
      const bool on_bound = r.x(i) == lower(i) || r.x(i) == upper(i);
      const bool should = std::find(active.begin(), active.end(), i) != active.end();
      CHECK(on_bound == should);
    }
  }
}

namespace {

struct BoxQp {
  MatrixXd h;
  VectorXd q, lower, upper;
  double value(const VectorXd& x) const { return 0.5 * x.dot(h * x) + q.dot(x); }
};

// The minimiser of a strictly convex box QP by enumerating all 3^n assignments (at lower, at
// upper, free) and keeping the KKT point: independent of any descent method.
VectorXd brute_force_box_qp(const BoxQp& qp) {
  const int n = static_cast<int>(qp.q.size());
  int total = 1;
  for (int i = 0; i < n; ++i) total *= 3;
  VectorXd best;
  double best_value = kInf;
  for (int code = 0; code < total; ++code) {
    std::vector<int> state(n), free;
    int c = code;
    VectorXd x = VectorXd::Zero(n);
    bool possible = true;
    for (int i = 0; i < n; ++i) {
      state[i] = c % 3;
      c /= 3;
      if (state[i] == 0) {
        if (!std::isfinite(qp.lower(i))) possible = false;
        x(i) = qp.lower(i);
      } else if (state[i] == 1) {
        if (!std::isfinite(qp.upper(i))) possible = false;
        x(i) = qp.upper(i);
      } else {
        free.push_back(i);
      }
    }
    if (!possible) continue;
    const int nf = static_cast<int>(free.size());
    if (nf > 0) {
      MatrixXd hff(nf, nf);
      VectorXd rhs(nf);
      for (int a = 0; a < nf; ++a) {
        rhs(a) = -qp.q(free[a]);
        for (int i = 0; i < n; ++i)
          if (state[i] != 2) rhs(a) -= qp.h(free[a], i) * x(i);
        for (int b = 0; b < nf; ++b) hff(a, b) = qp.h(free[a], free[b]);
      }
      const VectorXd xf = hff.llt().solve(rhs);
      for (int a = 0; a < nf; ++a) x(free[a]) = xf(a);
    }
    const VectorXd g = qp.h * x + qp.q;
    bool kkt = true;
    for (int i = 0; i < n && kkt; ++i) {
      if (state[i] == 2) kkt = x(i) >= qp.lower(i) - 1e-12 && x(i) <= qp.upper(i) + 1e-12;
      if (state[i] == 0) kkt = g(i) >= -1e-12;
      if (state[i] == 1) kkt = g(i) <= 1e-12;
    }
    if (kkt && qp.value(x) < best_value) {
      best_value = qp.value(x);
      best = x;
    }
  }
  return best;
}

}  // namespace

TEST_CASE("lbfgsb: random bounded convex quadratics match brute-force active-set enumeration") {
  Rng rng(20240501);
  int nondegenerate_checked = 0;
  for (int trial = 0; trial < 40; ++trial) {
    CAPTURE(trial);
    const int n = 2 + static_cast<int>(rng.below(6));  // 2..7
    BoxQp qp;
    MatrixXd g(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) g(i, j) = rng.uniform(-1.0, 1.0);
    qp.h = g.transpose() * g + 0.05 * MatrixXd::Identity(n, n);
    qp.q.resize(n);
    qp.lower.resize(n);
    qp.upper.resize(n);
    for (int i = 0; i < n; ++i) {
      qp.q(i) = rng.uniform(-3.0, 3.0);
      qp.lower(i) = rng.uniform(-1.0, 0.0);
      qp.upper(i) = rng.uniform(0.0, 1.0);
      const std::uint64_t kind = rng.below(8);
      if (kind == 0) qp.lower(i) = -kInf;
      if (kind == 1) qp.upper(i) = kInf;
      if (kind == 2) qp.upper(i) = qp.lower(i);  // fixed variable
    }
    const VectorXd expected = brute_force_box_qp(qp);
    REQUIRE(expected.size() == n);
    ObjectiveFunction f = [&qp](const VectorXd& x, VectorXd& grad) {
      grad = qp.h * x + qp.q;
      return qp.value(x);
    };
    LbfgsbOptions params;
    params.gradient_tolerance = 1e-12;
    params.function_tolerance = 0.0;
    params.memory = 5;
    VectorXd x0(n);
    for (int i = 0; i < n; ++i) x0(i) = rng.uniform(-2.0, 2.0);  // outside the box at times
    const LbfgsbResult r = lbfgsb_minimize(f, x0, qp.lower, qp.upper, params);
    CHECK(r.status == LbfgsbStatus::converged);
    CHECK((r.x - expected).lpNorm<Eigen::Infinity>() < 1e-8);
    // Compare active sets where the solution is not degenerate (clear multiplier or slack).
    const VectorXd grad = qp.h * expected + qp.q;
    bool clear = true;
    for (int i = 0; i < n; ++i) {
      const bool at_bound = expected(i) == qp.lower(i) || expected(i) == qp.upper(i);
      if (at_bound && std::fabs(grad(i)) < 1e-6 && qp.lower(i) != qp.upper(i)) clear = false;
      if (!at_bound && std::min(expected(i) - qp.lower(i), qp.upper(i) - expected(i)) < 1e-6)
        clear = false;
    }
    if (clear) {
      ++nondegenerate_checked;
      for (int i = 0; i < n; ++i) {
        const bool at_bound = expected(i) == qp.lower(i) || expected(i) == qp.upper(i);
        CHECK(at_bound == (r.x(i) == qp.lower(i) || r.x(i) == qp.upper(i)));
      }
    }
  }
  CHECK(nondegenerate_checked >= 30);
}

TEST_CASE("lbfgsb: constructed ill-conditioned bounded quadratic, n = 100, 40 active bounds") {
  // x* chosen with 20 variables on the lower and 20 on the upper bound with strict
  // complementarity; q = g* − H x* so that the KKT conditions hold exactly at x*.
  const int n = 100;
  Rng rng(7);
  MatrixXd g(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) g(i, j) = rng.uniform(-1.0, 1.0);
  VectorXd diag(n);
  for (int i = 0; i < n; ++i) diag(i) = std::pow(10.0, rng.uniform(-2.0, 1.0));
  const MatrixXd h = g.transpose() * g / n + MatrixXd(diag.asDiagonal());
  VectorXd x_star(n), g_star = VectorXd::Zero(n), lower(n), upper(n);
  for (int i = 0; i < n; ++i) {
    lower(i) = rng.uniform(-2.0, -1.0);
    upper(i) = rng.uniform(1.0, 2.0);
    if (i % 5 == 0) {
      x_star(i) = lower(i);
      g_star(i) = rng.uniform(0.1, 1.0);
    } else if (i % 5 == 1) {
      x_star(i) = upper(i);
      g_star(i) = -rng.uniform(0.1, 1.0);
    } else {
      x_star(i) = rng.uniform(-0.8, 0.8);
    }
  }
  const VectorXd q = g_star - h * x_star;
  ObjectiveFunction f = [&](const VectorXd& x, VectorXd& grad) {
    grad = h * x + q;
    return 0.5 * x.dot(h * x) + q.dot(x);
  };
  LbfgsbOptions params;
  params.gradient_tolerance = 1e-11;
  params.function_tolerance = 0.0;
  const LbfgsbResult r = lbfgsb_minimize(f, VectorXd::Zero(n), lower, upper, params);
  MESSAGE("status=" << std::string(to_string(r.status)) << " it=" << r.iterations
                    << " ev=" << r.evaluations << " pg=" << r.projected_gradient_norm);
  CHECK(r.status == LbfgsbStatus::converged);
  CHECK((r.x - x_star).lpNorm<Eigen::Infinity>() < 1e-8);
  for (int i = 0; i < n; ++i) {
    const bool should = i % 5 <= 1;
    CHECK(should == (r.x(i) == lower(i) || r.x(i) == upper(i)));
  }
}

TEST_CASE("lbfgsb: bad input is reported, not thrown") {
  ObjectiveFunction f = chained_rosenbrock;
  LbfgsbOptions bad;
  bad.memory = 0;
  CHECK(lbfgsb_minimize(f, VectorXd::Zero(3), VectorXd(), VectorXd(), bad).status ==
        LbfgsbStatus::invalid_input);
  CHECK(lbfgsb_minimize(f, VectorXd::Zero(3), VectorXd::Zero(2), VectorXd(), LbfgsbOptions()).status ==
        LbfgsbStatus::invalid_input);
  CHECK(lbfgsb_minimize(f, VectorXd::Zero(2), VectorXd::Constant(2, 1.0), VectorXd::Zero(2),
                        LbfgsbOptions()).status == LbfgsbStatus::invalid_input);
  VectorXd nan_start = VectorXd::Zero(2);
  nan_start(1) = std::numeric_limits<double>::quiet_NaN();
  CHECK(lbfgsb_minimize(f, nan_start, VectorXd(), VectorXd(), LbfgsbOptions()).status ==
        LbfgsbStatus::invalid_input);
  ObjectiveFunction nan_f = [](const VectorXd&, VectorXd& g) {
    g.setZero();
    return std::numeric_limits<double>::quiet_NaN();
  };
  CHECK(lbfgsb_minimize(nan_f, VectorXd::Zero(2), VectorXd(), VectorXd(), LbfgsbOptions()).status ==
        LbfgsbStatus::numerical_issue);
}

TEST_CASE("lbfgsb: non-finite trial values are backed off, and early stops keep the best iterate") {
  // f = −log-barrier-like: defined only for x < 1 (NaN beyond), minimum at x = 0.5 in each
  // coordinate; the first long steps land in the undefined region.
  ObjectiveFunction f = [](const VectorXd& x, VectorXd& g) {
    double v = 0.0;
    for (Eigen::Index i = 0; i < x.size(); ++i) {
      if (x(i) >= 1.0) {
        g.setConstant(std::numeric_limits<double>::quiet_NaN());
        return std::numeric_limits<double>::quiet_NaN();
      }
      const double t = 1.0 - x(i);
      v += x(i) * x(i) * 4.0 + 1.0 / t;  // minimum where 8x = 1/t²
      g(i) = 8.0 * x(i) + 1.0 / (t * t);
    }
    return v;
  };
  VectorXd x0 = VectorXd::Constant(4, -30.0);
  LbfgsbOptions params;
  params.gradient_tolerance = 1e-10;
  const LbfgsbResult r = lbfgsb_minimize(f, x0, VectorXd(), VectorXd(), params);
  CHECK(r.status == LbfgsbStatus::converged);
  VectorXd g(4);
  CHECK(std::isfinite(f(r.x, g)));
  CHECK(g.lpNorm<Eigen::Infinity>() < 1e-9);

  // Cap the iterations: the result is the best iterate, below the start value, and consistent.
  LbfgsbOptions capped;
  capped.max_iterations = 3;
  const LbfgsbResult c = lbfgsb_minimize(chained_rosenbrock, rosenbrock_start(10), VectorXd(),
                                         VectorXd(), capped);
  CHECK(c.status == LbfgsbStatus::max_iterations);
  CHECK(c.iterations == 3);
  VectorXd g0(10), gc(10);
  CHECK(c.f < chained_rosenbrock(rosenbrock_start(10), g0));
  CHECK(chained_rosenbrock(c.x, gc) == c.f);
  CHECK(gc == c.grad);
  LbfgsbOptions few_evals;
  few_evals.max_evaluations = 5;
  const LbfgsbResult e = lbfgsb_minimize(chained_rosenbrock, rosenbrock_start(10), VectorXd(),
                                         VectorXd(), few_evals);
  CHECK(e.status == LbfgsbStatus::max_evaluations);
  CHECK(e.evaluations <= 5);
  CHECK(e.f <= chained_rosenbrock(rosenbrock_start(10), g0));
}

TEST_CASE("lbfgsb: identical iterates on repeated runs") {
  auto run = [](std::vector<double>& trace) {
    ObjectiveFunction f = [&trace](const VectorXd& x, VectorXd& g) {
      trace.insert(trace.end(), x.data(), x.data() + x.size());
      return chained_rosenbrock(x, g);
    };
    VectorXd lower = VectorXd::Constant(30, -kInf), upper = VectorXd::Constant(30, 0.9);
    return lbfgsb_minimize(f, rosenbrock_start(30), lower, upper);
  };
  std::vector<double> t1, t2;
  const LbfgsbResult a = run(t1);
  const LbfgsbResult b = run(t2);
  CHECK(t1.size() > 100);
  CHECK(t1 == t2);
  CHECK(a.x == b.x);
  CHECK(a.iterations == b.iterations);
}

TEST_CASE("lbfgsb: a stop flag ends the run before its next iteration, with the lowest iterate") {
  // The flag is raised from inside the objective after `after` evaluations (in use it is raised by
  // another thread); the run must end `stopped` within that iteration's line search, having made
  // exactly the steps the unstopped run makes up to there.
  const int n = 10;
  std::vector<double> full_trace;
  LbfgsbOptions params;
  params.function_tolerance = 0.0;
  const auto traced = [](std::vector<double>& trace, std::atomic<bool>* raise, int after) {
    return [&trace, raise, after](const VectorXd& x, VectorXd& g) {
      trace.push_back(x(0));
      if (raise && static_cast<int>(trace.size()) == after) raise->store(true);
      return chained_rosenbrock(x, g);
    };
  };
  const LbfgsbResult full = lbfgsb_minimize(traced(full_trace, nullptr, 0), rosenbrock_start(n), VectorXd(), VectorXd(), params);
  REQUIRE(full.status == LbfgsbStatus::converged);
  for (int after : {1, 5, 20}) {
    CAPTURE(after);
    std::atomic<bool> stop{false};
    std::vector<double> trace;
    params.stop = &stop;
    const LbfgsbResult r = lbfgsb_minimize(traced(trace, &stop, after), rosenbrock_start(n), VectorXd(), VectorXd(), params);
    CHECK(r.status == LbfgsbStatus::stopped);
    CHECK(std::string(to_string(r.status)) == "stopped");
    CHECK(r.evaluations < full.evaluations);
    CHECK(r.evaluations <= after + params.max_line_search_evaluations);
    REQUIRE(trace.size() <= full_trace.size());
    CHECK(std::equal(trace.begin(), trace.end(), full_trace.begin()));
    VectorXd g(n);
    VectorXd start_gradient(n);
    CHECK(r.f <= chained_rosenbrock(rosenbrock_start(n), start_gradient));
    CHECK(r.f == chained_rosenbrock(r.x, g));
  }
  std::atomic<bool> raised{true};
  params.stop = &raised;
  const LbfgsbResult at_once = lbfgsb_minimize(chained_rosenbrock, rosenbrock_start(n), VectorXd(), VectorXd(), params);
  CHECK(at_once.status == LbfgsbStatus::stopped);
  CHECK(at_once.iterations == 0);
  CHECK(at_once.x == rosenbrock_start(n));
}
