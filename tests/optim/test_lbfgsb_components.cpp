// The parts of L-BFGS-B checked one by one against dense, independent computations:
// the compact matrix against explicit BFGS updates, the generalised Cauchy point against a dense
// walk along the projected-gradient path, the subspace step against a dense reduced Newton solve,
// and the Moré–Thuente search on the six test functions of its paper (strong Wolfe at the result,
// and the numbers of evaluations the paper reports, with xtol = 1e-10).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "optim/cauchy_point.h"
#include "optim/lbfgs_memory.h"
#include "optim/more_thuente.h"
#include "optim/subspace_minimization.h"
#include "util/det_math.h"
#include "util/rng.h"

using namespace offsetopt;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

MatrixXd random_spd(Rng& rng, int n, double shift) {
  MatrixXd g(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) g(i, j) = rng.uniform(-1.0, 1.0);
  return g.transpose() * g + shift * MatrixXd::Identity(n, n);
}

// Fills the memory with pairs y = A s (A SPD: s^T y > 0); returns the pairs, oldest first.
void fill_memory(Rng& rng, LbfgsMemory& memory, int n, int pairs, std::vector<VectorXd>& ss,
                 std::vector<VectorXd>& ys) {
  const MatrixXd a = random_spd(rng, n, 0.3);
  for (int k = 0; k < pairs; ++k) {
    VectorXd s(n);
    for (int i = 0; i < n; ++i) s(i) = rng.uniform(-1.0, 1.0);
    const VectorXd y = a * s;
    REQUIRE(memory.add(s, y));
    ss.push_back(s);
    ys.push_back(y);
  }
}

// Dense walk along x(t) = P(x − t g), segment by segment, with the explicit B; returns x^c.
VectorXd dense_cauchy(const VectorXd& x, const VectorXd& g, const VectorXd& lo, const VectorXd& hi,
                      const MatrixXd& b) {
  const int n = static_cast<int>(x.size());
  std::vector<double> t(n, kInf);
  for (int i = 0; i < n; ++i) {
    const bool stuck = lo(i) == hi(i) || (x(i) <= lo(i) && g(i) >= 0.0) || (x(i) >= hi(i) && g(i) <= 0.0);
    if (stuck) {
      t[i] = 0.0;
    } else if (g(i) < 0.0 && std::isfinite(hi(i))) {
      t[i] = (x(i) - hi(i)) / g(i);
    } else if (g(i) > 0.0 && std::isfinite(lo(i))) {
      t[i] = (x(i) - lo(i)) / g(i);
    }
  }
  std::vector<double> stops(t.begin(), t.end());
  stops.push_back(kInf);
  std::sort(stops.begin(), stops.end());
  auto point = [&](double tt) {
    VectorXd p = x;
    for (int i = 0; i < n; ++i) p(i) = x(i) - std::min(tt, t[i]) * g(i);
    return p;
  };
  double t_prev = 0.0;
  for (double t_next : stops) {
    if (t_next <= t_prev) continue;
    VectorXd d = VectorXd::Zero(n);
    for (int i = 0; i < n; ++i)
      if (t[i] > t_prev) d(i) = -g(i);
    const VectorXd z = point(t_prev) - x;
    const double slope = g.dot(d) + d.dot(b * z);
    const double curvature = d.dot(b * d);
    if (slope >= 0.0) return point(t_prev);
    const double t_star = t_prev - slope / curvature;
    if (t_star < t_next) return point(t_star);
    t_prev = t_next;
  }
  return point(t_prev);
}

}  // namespace

TEST_CASE("lbfgs-memory: compact form equals explicit BFGS updates of theta*I") {
  Rng rng(11);
  const int n = 9;
  for (int capacity : {1, 3, 5}) {
    LbfgsMemory memory(n, capacity);
    std::vector<VectorXd> ss, ys;
    fill_memory(rng, memory, n, 7, ss, ys);  // overflows: only the last `capacity` pairs remain
    const int p = memory.size();
    CHECK(p == capacity);
    const double theta = ys.back().dot(ys.back()) / ss.back().dot(ys.back());
    CHECK(memory.theta() == doctest::Approx(theta).epsilon(1e-14));
    MatrixXd b = theta * MatrixXd::Identity(n, n);
    for (size_t k = ss.size() - static_cast<size_t>(p); k < ss.size(); ++k) {
      const VectorXd bs = b * ss[k];
      b += -(bs * bs.transpose()) / ss[k].dot(bs) + (ys[k] * ys[k].transpose()) / ys[k].dot(ss[k]);
    }
    CHECK((memory.dense_b() - b).lpNorm<Eigen::Infinity>() < 1e-10 * b.lpNorm<Eigen::Infinity>());
    // M is the inverse of the middle matrix.
    const MatrixXd prod = memory.m() * memory.middle_inverse();
    CHECK((prod - MatrixXd::Identity(2 * p, 2 * p)).lpNorm<Eigen::Infinity>() < 1e-10);
  }
}

TEST_CASE("cauchy-point: matches a dense walk along the projected-gradient path") {
  Rng rng(12);
  for (int trial = 0; trial < 200; ++trial) {
    CAPTURE(trial);
    const int n = 3 + static_cast<int>(rng.below(10));
    LbfgsMemory memory(n, 4);
    std::vector<VectorXd> ss, ys;
    fill_memory(rng, memory, n, static_cast<int>(rng.below(6)), ss, ys);  // 0..5 pairs
    VectorXd lo(n), hi(n), x(n), g(n);
    for (int i = 0; i < n; ++i) {
      lo(i) = rng.uniform(-1.0, 0.0);
      hi(i) = rng.uniform(0.0, 1.0);
      const std::uint64_t kind = rng.below(10);
      if (kind == 0) lo(i) = -kInf;
      if (kind == 1) hi(i) = kInf;
      x(i) = rng.uniform(std::isfinite(lo(i)) ? lo(i) : -2.0, std::isfinite(hi(i)) ? hi(i) : 2.0);
      if (kind == 2 && std::isfinite(lo(i))) x(i) = lo(i);  // start on a bound
      if (kind == 3 && std::isfinite(hi(i))) x(i) = hi(i);
      g(i) = rng.uniform(-3.0, 3.0);
      if (kind == 4) g(i) = 0.0;
    }
    const CauchyPoint cp = generalized_cauchy_point(x, g, lo, hi, memory);
    const VectorXd expected = dense_cauchy(x, g, lo, hi, memory.dense_b());
    CHECK((cp.x - expected).lpNorm<Eigen::Infinity>() < 1e-10);
    CHECK((cp.c - memory.w().transpose() * (cp.x - x)).lpNorm<Eigen::Infinity>() < 1e-10);
    for (int i = 0; i < n; ++i) {
      CHECK(cp.x(i) >= lo(i));
      CHECK(cp.x(i) <= hi(i));
    }
  }
}

TEST_CASE("subspace-minimization: direction solves the dense reduced Newton system") {
  Rng rng(13);
  for (int trial = 0; trial < 100; ++trial) {
    CAPTURE(trial);
    const int n = 4 + static_cast<int>(rng.below(10));
    LbfgsMemory memory(n, 5);
    std::vector<VectorXd> ss, ys;
    fill_memory(rng, memory, n, 1 + static_cast<int>(rng.below(6)), ss, ys);
    VectorXd lo(n), hi(n), x(n), g(n);
    for (int i = 0; i < n; ++i) {
      lo(i) = rng.uniform(-1.0, -0.2);
      hi(i) = rng.uniform(0.2, 1.0);
      x(i) = rng.uniform(lo(i), hi(i));
      g(i) = rng.uniform(-2.0, 2.0);
    }
    const CauchyPoint cp = generalized_cauchy_point(x, g, lo, hi, memory);
    const SubspaceStep step = subspace_minimization(x, g, lo, hi, memory, cp);
    REQUIRE(step.ok);
    const int nf = static_cast<int>(cp.free.size());
    if (nf == 0) continue;
    const MatrixXd b = memory.dense_b();
    const VectorXd full_r = g + b * (cp.x - x);
    MatrixXd bff(nf, nf);
    VectorXd r(nf);
    for (int a = 0; a < nf; ++a) {
      r(a) = full_r(cp.free[a]);
      for (int c = 0; c < nf; ++c) bff(a, c) = b(cp.free[a], cp.free[c]);
    }
    const VectorXd expected = -bff.ldlt().solve(r);
    CHECK((step.direction - expected).lpNorm<Eigen::Infinity>() <
          1e-9 * std::max(1.0, expected.lpNorm<Eigen::Infinity>()));
    for (int i = 0; i < n; ++i) {
      CHECK(step.x_bar(i) >= lo(i));
      CHECK(step.x_bar(i) <= hi(i));
    }
    CHECK(g.dot(step.x_bar - x) <= 1e-14);  // a descent (or zero) direction
  }
}

namespace {

struct LineFunction {
  std::string name;
  double ftol, gtol;
  std::vector<int> published_evaluations;  // Moré & Thuente 1994, Tables 1–6, a0 = 1e-3..1e3
  std::function<void(double, double&, double&)> phi;
};

std::vector<LineFunction> more_thuente_functions() {
  std::vector<LineFunction> fs;
  fs.push_back({"MT1", 1e-3, 1e-1, {6, 3, 1, 4}, [](double a, double& f, double& g) {
                  const double beta = 2.0;
                  f = -a / (a * a + beta);
                  g = (a * a - beta) / ((a * a + beta) * (a * a + beta));
                }});
  fs.push_back({"MT2", 1e-1, 1e-1, {12, 8, 8, 11}, [](double a, double& f, double& g) {
                  const double beta = 0.004;
                  const double s = a + beta;
                  f = s * s * s * s * s - 2.0 * s * s * s * s;
                  g = 5.0 * s * s * s * s - 8.0 * s * s * s;
                }});
  fs.push_back({"MT3", 1e-1, 1e-1, {12, 12, 10, 13}, [](double a, double& f, double& g) {
                  const double beta = 0.01, l = 39.0;
                  double f0, g0;
                  if (a <= 1.0 - beta) {
                    f0 = 1.0 - a;
                    g0 = -1.0;
                  } else if (a >= 1.0 + beta) {
                    f0 = a - 1.0;
                    g0 = 1.0;
                  } else {
                    f0 = (a - 1.0) * (a - 1.0) / (2.0 * beta) + beta / 2.0;
                    g0 = (a - 1.0) / beta;
                  }
                  double s, c;
                  det_sincos(l * kPi * a / 2.0, s, c);
                  f = f0 + 2.0 * (1.0 - beta) / (l * kPi) * s;
                  g = g0 + (1.0 - beta) * c;
                }});
  auto yanai = [](double b1, double b2) {
    return [b1, b2](double a, double& f, double& g) {
      const double g1 = std::sqrt(1.0 + b1 * b1) - b1;
      const double g2 = std::sqrt(1.0 + b2 * b2) - b2;
      const double r1 = std::sqrt((1.0 - a) * (1.0 - a) + b2 * b2);
      const double r2 = std::sqrt(a * a + b1 * b1);
      f = g1 * r1 + g2 * r2;
      g = -g1 * (1.0 - a) / r1 + g2 * a / r2;
    };
  };
  fs.push_back({"MT4", 1e-3, 1e-3, {4, 1, 3, 4}, yanai(0.001, 0.001)});
  fs.push_back({"MT5", 1e-3, 1e-3, {6, 3, 7, 8}, yanai(0.01, 0.001)});
  fs.push_back({"MT6", 1e-3, 1e-3, {13, 11, 8, 11}, yanai(0.001, 0.01)});
  return fs;
}

}  // namespace

TEST_CASE("more-thuente: strong Wolfe steps with the paper's evaluation counts on its six functions") {
  for (const LineFunction& fn : more_thuente_functions()) {
    const double starts[4] = {1e-3, 1e-1, 1e1, 1e3};
    for (int k = 0; k < 4; ++k) {
      const double a0 = starts[k];
      CAPTURE(fn.name);
      CAPTURE(a0);
      double f0, g0;
      fn.phi(0.0, f0, g0);
      REQUIRE(g0 < 0.0);
      MoreThuenteOptions st;
      st.ftol = fn.ftol;
      st.gtol = fn.gtol;
      st.xtol = 1e-10;
      st.stpmin = 0.0;
      st.stpmax = 1e10;
      MoreThuenteSearch search;
      MoreThuenteStatus state = search.start(f0, g0, a0, st);
      int evals = 0;
      double f = 0.0, g = 0.0, a = 0.0;
      while (state == MoreThuenteStatus::evaluate && evals < 50) {
        a = search.step();
        fn.phi(a, f, g);
        ++evals;
        state = search.advance(f, g);
      }
      MESSAGE(fn.name << " a0=" << a0 << " evals=" << evals << " a=" << a << " g=" << g);
      CHECK(state == MoreThuenteStatus::converged);
      CHECK(f <= f0 + fn.ftol * a * g0);
      CHECK(std::fabs(g) <= fn.gtol * std::fabs(g0));
      CHECK(evals == fn.published_evaluations[static_cast<size_t>(k)]);
    }
  }
}

TEST_CASE("more-thuente: bad options are named by check() and end the search with error") {
  CHECK(MoreThuenteOptions{}.check().empty());
  MoreThuenteOptions options;
  options.stpmin = 2.0;
  options.stpmax = 1.0;
  CHECK(options.check() == "stpmax must be >= stpmin");
  MoreThuenteSearch search;
  CHECK(search.start(1.0, -1.0, 1.5, options) == MoreThuenteStatus::error);
  options = MoreThuenteOptions{};
  options.xtol = -1.0;
  CHECK(options.check() == "xtol must be >= 0");
  CHECK(search.start(1.0, -1.0, 1.0, options) == MoreThuenteStatus::error);
  CHECK(search.start(1.0, -1.0, 1.0, MoreThuenteOptions{}) == MoreThuenteStatus::evaluate);
}
