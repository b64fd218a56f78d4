// L-BFGS-B: limited-memory quasi-Newton minimisation subject to simple bounds
//   minimise f(x)  subject to  lower ≤ x ≤ upper   (x of length n; ±infinity = no bound)
// after R. H. Byrd, P. Lu, J. Nocedal and C. Zhu, "A limited memory algorithm for bound
// constrained optimization", SIAM J. Sci. Comput. 16(5), 1995, and the Fortran code v3.0
// (C. Zhu, R. Byrd, J. Nocedal, J. L. Morales; Morales & Nocedal, ACM TOMS 38(1), 2011).
//
// Each iteration: the generalised Cauchy point (optim/cauchy_point.h) on the compact
// limited-memory model (optim/lbfgs_memory.h), subspace minimisation over the free variables by
// the direct primal method (optim/subspace_minimization.h), then a Moré–Thuente line search
// (optim/more_thuente.h) for the strong Wolfe conditions along d = x̄ − x_k, with steps limited to
// the box. The correction pair is skipped when s^T y ≤ ε·(−g^T s). A failed line search, a
// non-descent direction or a singular reduced system resets the memory and retries from the same
// point (as the Fortran code does); it fails only with an empty memory.
//
// Every accepted step decreases f (up to function_noise, see below), and the iterate with the
// lowest f is returned when the run stops early. Nothing is thrown: bad input and numerical
// trouble come back as a status.
//
// Deliberate differences from the Fortran code: breakpoints are sorted (ties by index) instead
// of kept in a heap (same order, simpler); when the line search ends on a warning or its cap,
// the lowest trial point with sufficient decrease is taken instead of the last trial (keeps f
// monotone); a non-finite f or ∇f at a trial point halves the step instead of aborting; the
// relative-reduction test has no floor of 1; and the approximate Wolfe acceptance below.
#pragma once
#include <atomic>
#include <functional>
#include <string>

#include <Eigen/Core>

namespace offsetopt {

// f(x, grad): returns f(x) and writes ∇f(x) into grad (already sized n). A non-finite value or
// gradient is allowed and treated as "step too long" inside the line search.
using ObjectiveFunction = std::function<double(const Eigen::VectorXd& x, Eigen::VectorXd& grad)>;

struct LbfgsbOptions {
  // Number of correction pairs kept (the "m" of the paper). 3..20 is the usual range.
  int memory = 10;
  // converged when ‖P(x − ∇f) − x‖_∞ ≤ max(gradient_tolerance,
  // relative_gradient_tolerance · ‖P(x0 − ∇f(x0)) − x0‖_∞)  (P: projection onto the box).
  // Absolute in units of ∇f; the relative part makes the test independent of the objective's
  // scale. Either may be 0, not both.
  double gradient_tolerance = 1e-8;
  double relative_gradient_tolerance = 0.0;
  // Stops (small_reduction) when f_k − f_{k+1} ≤ function_tolerance · max(|f_k|, |f_{k+1}|):
  // a relative test (no floor of 1, unlike the Fortran code, because objectives here can be
  // ~1e-3). 0 disables it.
  double function_tolerance = 1e-14;
  // Near a minimiser, differences of f fall below its rounding error long before ∇f is small
  // (|Δf| ~ |∇f|²/‖H‖). A trial step whose f rises by at most function_noise·|f(x_k)| is then
  // accepted on the derivative alone by the approximate Wolfe conditions of Hager & Zhang
  // (SIAM J. Optim. 16(1), 2005): (2δ−1)φ'(0) ≥ φ'(α) ≥ σφ'(0) with δ = wolfe_decrease,
  // σ = wolfe_curvature. 0 disables it. After max_noise_steps consecutive steps that neither
  // decrease f nor reach a new lowest projected-gradient norm the run stops with
  // small_reduction; the lowest f seen is returned whenever the run does not end converged.
  double function_noise = 1e-12;
  int max_noise_steps = 5;
  int max_iterations = 10000;
  int max_evaluations = 50000;
  // Strong Wolfe constants of the line search (Fortran defaults) and its per-search cap.
  double wolfe_decrease = 1e-3;   // ftol, in (0, wolfe_curvature)
  double wolfe_curvature = 0.9;   // gtol, in (wolfe_decrease, 1)
  double line_search_xtol = 0.1;  // relative bracket width at which the line search gives up
  int max_line_search_evaluations = 20;
  // When set (by another thread, whose work makes this run's result useless), the run ends with
  // `stopped` before its next iteration; the lowest iterate so far is returned. Not owned.
  const std::atomic<bool>* stop = nullptr;

  // Empty when valid, else what is wrong (one line).
  std::string check() const;
};

enum class LbfgsbStatus {
  converged,           // projected-gradient test met
  small_reduction,     // relative reduction of f below function_tolerance, or only noise-level
                       // steps: no further progress measurable
  max_iterations,      // iteration cap reached
  max_evaluations,     // evaluation cap reached
  line_search_failed,  // no acceptable step even along the projected steepest-descent path
  stopped,             // LbfgsbOptions::stop was set
  numerical_issue,     // f or ∇f not finite at the start point
  invalid_input        // parameters, sizes, bounds (lower > upper) or start point not valid
};

const char* to_string(LbfgsbStatus status);

struct LbfgsbResult {
  LbfgsbStatus status = LbfgsbStatus::invalid_input;
  Eigen::VectorXd x;     // best iterate (start point projected onto the box if nothing better)
  double f = 0.0;        // f(x)
  Eigen::VectorXd grad;  // ∇f(x)
  double projected_gradient_norm = 0.0;  // ‖P(x − ∇f) − x‖_∞ at x
  int iterations = 0;                    // accepted steps
  int evaluations = 0;                   // calls of f
  int memory_resets = 0;                 // restarts from steepest descent
  std::string message;                   // for invalid_input: what was wrong
};

// lower/upper: length n, or empty for "no bounds"; entries may be ±infinity.
LbfgsbResult lbfgsb_minimize(const ObjectiveFunction& f, const Eigen::VectorXd& x0,
                             const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                             const LbfgsbOptions& params = LbfgsbOptions());

// ‖P(x − g) − x‖_∞ for x inside the box.
double projected_gradient_norm(const Eigen::VectorXd& x, const Eigen::VectorXd& g,
                               const Eigen::VectorXd& lower, const Eigen::VectorXd& upper);

}  // namespace offsetopt
