// Benchmark of the augmented Lagrangian on the 100,000-row linear block problem of
// tests/optim/linear_block_problem.h (36 variables; solution known by construction).
// Prints evaluations, iterations, seconds and the accuracy reached. Run: bench/optim/run.sh
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "../../tests/optim/linear_block_problem.h"
#include "optim/augmented_lagrangian.h"

using namespace offsetopt;

int main(int argc, char** argv) {
  const int m = argc > 1 ? std::atoi(argv[1]) : 100000;
  const int n = argc > 2 ? std::atoi(argv[2]) : 36;
  const bool trace = argc > 3 && argv[3][0] == 't';
  using clock = std::chrono::steady_clock;

  const auto t0 = clock::now();
  const LinearBlockProblem lb = make_linear_block_problem(m, n, 2015);
  const auto t1 = clock::now();

  // Cost of one evaluation's two products, for reference.
  Eigen::VectorXd x = Eigen::VectorXd::Constant(n, 0.1), ax(m), g(n);
  const int reps = 20;
  const auto tp0 = clock::now();
  for (int r = 0; r < reps; ++r) {
    ax.noalias() = lb.a * x;
    g.noalias() = lb.a.transpose() * ax;
    x(0) += 1e-3 * g(0) / (1.0 + std::abs(g(0)));
  }
  const auto tp1 = clock::now();

  AlOptions params;
  if (argc > 4) params.inner.memory = std::atoi(argv[4]);
  if (trace) {
    params.on_outer_iteration = [](const AlIterationInfo& it) {
      std::printf("  outer %2d  f=%.10g  viol=%.3e  stat=%.3e  compl=%.3e  rho=%.1e  inner=%s/%d  evals=%d\n",
                  it.outer_iteration, it.f, it.max_violation, it.stationarity, it.complementarity,
                  it.penalty, to_string(it.inner_status), it.inner_iterations, it.evaluations);
    };
  }
  ConstrainedProblem p = lb.problem();
  const auto t2 = clock::now();
  const AlResult r = augmented_lagrangian_minimize(p, Eigen::VectorXd::Zero(n), params);
  const auto t3 = clock::now();

  auto sec = [](clock::time_point a, clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
  };
  std::printf("linear block problem: m = %d rows, n = %d variables\n", m, n);
  std::printf("  problem generation        %.3f s\n", sec(t0, t1));
  std::printf("  A x + A^T y (one pair)    %.3f ms\n", 1e3 * sec(tp0, tp1) / reps);
  std::printf("  solve                     %.3f s\n", sec(t2, t3));
  std::printf("  status                    %s\n", to_string(r.status));
  std::printf("  outer iterations          %d\n", r.outer_iterations);
  std::printf("  inner iterations          %d\n", r.inner_iterations);
  std::printf("  evaluations               %d\n", r.evaluations);
  std::printf("  seconds per evaluation    %.3f ms\n", 1e3 * sec(t2, t3) / r.evaluations);
  std::printf("  |x - x*|_inf              %.3e\n", (r.x - lb.x_star).lpNorm<Eigen::Infinity>());
  std::printf("  |f - f*| / |f*|           %.3e\n", std::abs(r.f - lb.f_star) / std::abs(lb.f_star));
  std::printf("  max violation             %.3e\n", r.max_violation);
  std::printf("  stationarity (scaled)     %.3e\n", r.stationarity);
  return r.status == AlStatus::converged ? 0 : 1;
}
