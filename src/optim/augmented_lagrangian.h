// src/optim (this is the folder's main header): the optimisers of the reduced problem, knowing
// nothing of meshes. It owns L-BFGS-B (lbfgsb.h, with its Cauchy point, subspace minimisation,
// limited memory and Moré–Thuente line search), the augmented Lagrangian that drives it (this
// header) and the finite-difference gradient and Jacobian checker. Layer: just above util; it may
// include util and itself only (and Eigen).
//
// Augmented Lagrangian method (Powell–Hestenes–Rockafellar), as in LANCELOT and ALGENCAN
// (R. Andreani, E. G. Birgin, J. M. Martínez, M. L. Schuverdt, "On augmented Lagrangian methods
// with general lower-level constraints", SIAM J. Optim. 18(4), 2007; E. G. Birgin and
// J. M. Martínez, "Practical Augmented Lagrangian Methods for Constrained Optimization", SIAM 2014),
// with L-BFGS-B (optim/lbfgsb.h) for the bound-constrained subproblems:
//
//   minimise f(x)  subject to  h(x) = 0,  c(x) ≤ 0,  lower ≤ x ≤ upper,  lA ≤ A x ≤ uA
//
// Every constraint row is treated as lo_i ≤ c_i(x) ≤ hi_i (equality: lo = hi = 0; inequality:
// lo = −∞, hi = 0; linear rows: [lA_i, uA_i]). With row scales s_i and multiplier estimates ν̄_i
// the subproblem minimises, over the box,
//   L(x) = s_f f(x) + Σ_i (ρ/2) dist(s_i c_i(x) + ν̄_i/ρ, [s_i lo_i, s_i hi_i])²
// whose gradient is s_f ∇f + Σ_i ν_i s_i ∇c_i with ν_i = ρ (t_i − proj(t_i)), t_i = s_i c_i + ν̄_i/ρ:
// the first-order multiplier update. Sign convention of the multipliers returned (unscaled):
//   ∇f + J_h^T λ + J_c^T μ + A^T ν + (bound multipliers) = 0,  μ ≥ 0,
//   ν_i > 0 where the upper side of row i is active, ν_i < 0 where the lower side is.
// Penalty: ρ ← 10ρ whenever the feasibility-complementarity measure
// V = ‖s_i c_i − proj(s_i c_i + ν̄_i/ρ)‖_∞ fails to drop below half its previous value; the
// multipliers used in a subproblem are the estimates clipped to ±max_multiplier (safeguard).
//
// Scaling (ALGENCAN): s_f = 1/max(scale_floor, ‖∇f(x0)‖_∞), s_i = 1/max(scale_floor, ‖∇c_i(x0)‖_∞)
// (for linear rows the row's ∞-norm); scale_floor = 1 means only large gradients are scaled down.
//
// The block lA ≤ A x ≤ uA (A dense, m by n, m up to ~10⁶) is evaluated as one product A x and one
// A^T w per evaluation, never row by row through callbacks; A is referenced, not copied.
//
// Stopping: converged when max(unscaled, scaled) violation ≤ feasibility_tolerance, the projected
// gradient of the scaled Lagrangian ≤ stationarity_tolerance and the scaled complementarity
// min(|ν_i|, distance to the active side) ≤ complementarity_tolerance. infeasible when the
// violation stagnates while ρ grows and a direct minimisation of the scaled violation
// ½ Σ (s_i dist(c_i, [lo_i, hi_i]))² over the box ends stationary above the tolerance: the result
// then holds that least-violation point (a local one, for nonconvex constraints).
#pragma once
#include <atomic>
#include <functional>
#include <string>

#include <Eigen/Core>

#include "optim/lbfgsb.h"

namespace offsetopt {

// values (length count) and jacobian (count by n) arrive sized; the callee overwrites every entry.
using ConstraintFunction = std::function<void(const Eigen::VectorXd& x, Eigen::VectorXd& values,
                                              Eigen::MatrixXd& jacobian)>;

struct ConstrainedProblem {
  int num_variables = 0;
  ObjectiveFunction objective;  // f(x), ∇f(x)
  int num_equality = 0;         // h(x) = 0
  ConstraintFunction equality;
  int num_inequality = 0;  // c(x) ≤ 0
  ConstraintFunction inequality;
  Eigen::VectorXd lower, upper;  // simple bounds: empty or length n, ±infinity allowed
  // Linear block linear_lower ≤ A x ≤ linear_upper, A m by n (m may be 0 / nullptr). Not copied:
  // the matrix must outlive the call. Bounds of length m, ±infinity allowed.
  const Eigen::MatrixXd* linear_matrix = nullptr;
  Eigen::VectorXd linear_lower, linear_upper;
  // Optional, both or neither, for a problem whose rows share one costly chain rule (the reduced
  // problem: every row reads 20 integrals, and their derivatives cost O(#V·k) to project, so one
  // combined projection costs what one row's does). `values`: f and every nonlinear row
  // (equalities, then inequalities) into `rows` (sized), no derivatives. `weighted_gradient`, at
  // the point of the last `values` call: the gradient of objective_weight·f + Σ_i row_weights_i·row_i
  // into `grad` (sized). With them the subproblems ask for nothing else; the callbacks above are
  // still required, for the row scales at the start point.
  std::function<double(const Eigen::VectorXd& x, Eigen::VectorXd& rows)> values;
  std::function<void(const Eigen::VectorXd& x, double objective_weight, const Eigen::VectorXd& row_weights,
                     Eigen::VectorXd& grad)>
      weighted_gradient;
};

// Reported after every outer iteration (for progress output; the solver itself never prints).
struct AlIterationInfo {
  int outer_iteration = 0;
  double f = 0.0;
  double max_violation = 0.0;     // unscaled
  double stationarity = 0.0;      // subproblem's projected-gradient norm (scaled)
  double complementarity = 0.0;
  double penalty = 0.0;           // ρ used in this subproblem
  LbfgsbStatus inner_status = LbfgsbStatus::converged;
  int inner_iterations = 0;
  int evaluations = 0;            // total so far
};

struct AlOptions {
  double feasibility_tolerance = 1e-8;      // ∞-norm of the violation (unscaled and scaled)
  double stationarity_tolerance = 1e-8;     // ∞-norm of the scaled Lagrangian's projected gradient
  double complementarity_tolerance = 1e-8;  // scaled, see the header comment
  int max_outer_iterations = 50;
  int max_evaluations = 200000;  // evaluations of f (and of all constraints with it), in total
  double initial_penalty = 0.0;  // 0: ALGENCAN's choice 10 max(1,|f|)/max(1, ½‖viol‖²) in [1e-8, 1e8]
  // Warm start: multiplier estimates in AlResult's convention (unscaled), for example those of a
  // solve of a nearby problem; empty means zero, otherwise the sizes must match the problem's.
  Eigen::VectorXd initial_equality_multipliers, initial_inequality_multipliers;
  double penalty_increase = 10.0;
  double required_decrease = 0.5;  // V must fall below this fraction of its previous value
  double max_penalty = 1e20;
  double max_multiplier = 1e20;
  double scale_floor = 1.0;                 // see "Scaling"; 0 disables scaling entirely
  // Subproblem k+1 is solved to max(stationarity_tolerance, min(initial_inner_tolerance,
  // inner_tolerance_decrease · V_k)): only as accurately as the current infeasibility V_k
  // warrants (LANCELOT/ALGENCAN spirit), to stationarity_tolerance once feasible.
  double initial_inner_tolerance = 1e-4;
  double inner_tolerance_decrease = 0.1;
  int infeasibility_patience = 3;  // outer iterations of stagnant violation before the check
  // When > 0: a violation above this many times the feasibility tolerance that stagnates for one
  // outer iteration is checked at once (far from feasible, stagnation under a growing penalty
  // rarely recovers, and every later subproblem is worse conditioned than the last).
  double clear_violation_factor = 0.0;
  int stall_patience = 3;  // feasible outer iterations whose subproblem cannot progress → stalled
  LbfgsbOptions inner;  // memory, caps and line search of the subproblem solver; its gradient
                       // tolerance is set by the outer loop
  std::function<void(const AlIterationInfo&)> on_outer_iteration;  // optional observer
  // When set (by another thread), the run ends with `stopped` at its next outer iteration, and
  // every subproblem in flight ends at its next iteration (the inner options' stop is this one).
  const std::atomic<bool>* stop = nullptr;
  // Hand-off: the first outer iteration that ends with its violation (unscaled and scaled) within
  // hand_off_violation, without having converged, asks hand_off(x) once; true ends the run there
  // with `handed_off` (x that iterate, the multipliers and the penalty as they are), for a caller
  // that will solve a nearby problem from it anyway. It must not change what the run reads: when
  // it returns false, the run goes on exactly as without it.
  std::function<bool(const Eigen::VectorXd&)> hand_off;
  double hand_off_violation = 0.0;
  // Inner defaults: no relative-reduction stop (the projected-gradient and noise tests decide),
  // and 20 pairs instead of 10 because the subproblems are ill-conditioned (ρ‖∇c‖² against the
  // objective's curvature): on the 100,000-row benchmark 20 pairs need 40% fewer evaluations.
  AlOptions() {
    inner.function_tolerance = 0.0;
    inner.max_iterations = 2000;
    inner.memory = 20;
  }

  // Empty when valid, else what is wrong (one line; the inner options' prefixed "inner: ").
  std::string check() const;
};

enum class AlStatus {
  converged,             // feasibility, stationarity and complementarity tolerances met
  infeasible,            // no feasible point found: x is a (local) least-violation point
  stalled,               // feasible (and complementary) to tolerance, but the subproblems stopped
                         // making progress before the stationarity tolerance (gradient noise)
  max_outer_iterations,  // outer cap reached
  max_evaluations,       // evaluation cap reached
  stopped,               // AlOptions::stop was set: x is the last iterate, no claim is made
  handed_off,            // AlOptions::hand_off took the iterate: violation within hand_off_violation
  numerical_issue,       // f or a constraint not finite at the start point
  invalid_input          // sizes, bounds or parameters not valid (message says which)
};

const char* to_string(AlStatus status);

struct AlResult {
  AlStatus status = AlStatus::invalid_input;
  Eigen::VectorXd x;                   // final iterate (least-violation point when infeasible)
  double f = 0.0;                      // f(x)
  double max_violation = 0.0;          // max_i dist(c_i(x), [lo_i, hi_i]), unscaled, over all rows
  double scaled_violation = 0.0;       // the same on scaled rows
  double stationarity = 0.0;           // last subproblem's projected-gradient norm (scaled)
  double complementarity = 0.0;        // scaled
  Eigen::VectorXd equality_multipliers;    // λ (num_equality)
  Eigen::VectorXd inequality_multipliers;  // μ ≥ 0 (num_inequality)
  Eigen::VectorXd linear_multipliers;      // ν (m)
  Eigen::VectorXd equality_values;         // h(x)
  Eigen::VectorXd inequality_values;       // c(x)
  double penalty = 0.0;                    // final ρ
  int outer_iterations = 0;
  int inner_iterations = 0;  // L-BFGS-B iterations summed over subproblems
  int evaluations = 0;       // objective evaluations (each with all constraints)
  std::string message;       // for invalid_input: what was wrong
};

AlResult augmented_lagrangian_minimize(const ConstrainedProblem& problem, const Eigen::VectorXd& x0,
                                       const AlOptions& params = AlOptions());

}  // namespace offsetopt
