// src/shape (this is the folder's main header): the offset model and the goals: the offset
// field, smooth clamp, --fix regions, goals and the reduced problem. It may include every folder
// below it (util, optim, mesh, geometry, io, meshio, sparse, spectral, skeleton, mass) and itself;
// src/cavity and src/optimize sit above it.
//
// The reduced-order offset problem (Musialski et al. 2015, eq. 3, in the form docs/design.md "Reduced
// problem" fixes). With Γ the #V by k basis (manifold harmonics; rows of fixed vertices zeroed,
// paper 5.2) the variables are x = [α] or, with outer offsets, x = [α; β]:
//   outer offset  δout = smoothclamp(Γβ, −min(omax_i, (hi−δl)₊/2), omax_i)   along w (outward),
//   inner offset  δin  = smoothclamp(Γα, lo, hi),  lo = min(δl − δout, hi)   along v (inward),
// so the wall δin + δout ≥ δl and the skeleton bound δin ≤ hi hold by construction (clamp mode).
// In hard mode (the paper's formulation, for comparison) δin = Γα and δout = Γβ unclamped, and
// the bounds become the linear rows δl ≤ Γα ≤ hi (or, with outer offsets, −omax ≤ Γβ ≤ omax and
// Γα + Γβ ≥ δl, Γα ≤ hi) handed to the solver's linear block.
//   inner surface  x_in,i  = x_i + δin_i v_i,   outer surface  x_out,i = x_i + δout_i w_i.
// The goal (shape/goal.h) is evaluated on the volume integrals of both surfaces (measured from the
// frame origin) and its derivatives are chained exactly:
//   ∂row/∂α = (∂row/∂I_in) (∂I_in/∂δin) diag(∂δin/∂(Γα)) Γ,   O(#F + 10·#V·k) per evaluation
// with every row's derivatives (evaluate); the solver asks for one weighted sum of them per point
// (constrained_problem's values and weighted_gradient), O(#F + #V·k).
// The outer penalty wp·β₁² (paper 5.2: the first coefficient, the DC term) and, in clamp mode,
// the overshoot term (ReducedOptions::overshoot_weight) are added to f.
#pragma once
#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mass/volume_integrals.h"
#include "mesh/mesh.h"
#include "optim/augmented_lagrangian.h"
#include "shape/goal.h"

namespace offsetopt {

class WorkerPool;

// Per-vertex offset directions and bounds in the mesh's frame.
struct OffsetBand {
  Vertices inner_direction;  // v, #V by 3 (unit, inward)
  Vertices outer_direction;  // w, #V by 3 (unit, outward)
  Eigen::VectorXd lower;     // δl: the inner offset that leaves the wall thickness, #V
  Eigen::VectorXd upper;     // hi: the largest inner offset (skeleton distance less the gap), #V, >= 0
  std::vector<char> fixed;   // #V; nonzero: both offsets are 0 there (an opening)
  Eigen::VectorXd outer_limit;  // omax_i >= 0 per vertex (0 keeps the outer surface in place);
                                // empty when there are no outer offsets
};

enum class BoundsMode { clamp, hard };

struct ReducedOptions {
  double ramp_width = 2e-3;   // τ of the smooth clamp, in the mesh's units (> 0)
  bool outer = false;         // optimise an outer offset too
  double outer_penalty = 0.0; // wp >= 0
  BoundsMode bounds = BoundsMode::clamp;
  // Weight μ of the overshoot term μ · mean_i (raw_i − clamped_i)² added to f (raw = Γα or Γβ):
  // where the clamp saturates its slope is 0 and the constraints lose their gradient; the term
  // keeps the raw offsets near their band so the solver can still move every vertex. 0 disables.
  double overshoot_weight = 1.0;
  // Start: the least-squares fit of Γα to lo + start_fraction (hi − lo) (β = 0).
  double start_fraction = 0.5;
  // Each evaluation is cut into two fixed parts, run on two threads when this is > 1 and the mesh
  // is large enough (util/parallel.h's execution_policy; the results are the same either way).
  int threads = 2;
  // While this reads true, the two parts run one after the other on the calling thread: another
  // task holds the second core (optimize's reachability programme), and two parts on one core
  // wait for each other's time slices (on stand-filled --outer the first solve took 0.20 s beside
  // the programme, 0.16 s alone on one thread). Null: no such task.
  const std::atomic<bool>* serial_while = nullptr;

  // Empty when the options are valid, else what is wrong.
  std::string check() const;
};

class ReducedProblem {
 public:
  // `basis` is #V by k; an empty (0-column) basis with identity_basis = true means the
  // per-vertex problem of paper eq. (1) (Γ = I, k = #V). The mesh, band and basis are copied.
  ReducedProblem(const Mesh& mesh, const OffsetBand& band, const Eigen::MatrixXd& basis, bool identity_basis,
                 const GoalSpec& goal, const ReducedOptions& options);
  ~ReducedProblem();

  int num_variables() const { return options_.outer ? 2 * k_ : k_; }

  struct Evaluation {
    Eigen::VectorXd x;
    Eigen::VectorXd inner_offset, outer_offset;  // δin, δout (#V)
    Eigen::VectorXd inner_slope;                 // ∂δin/∂(Γα), in [0, 1] (1 in hard mode)
    Vector10d inner_integrals, outer_integrals;  // from the frame origin
    GoalValues goal;
    double objective = 0.0;                      // goal objective + outer penalty
    Eigen::VectorXd objective_gradient;          // num_variables
    Eigen::MatrixXd equality_jacobian, inequality_jacobian;  // rows by num_variables
  };

  // Evaluates at x; the last evaluation is cached (the solver asks for f, h and c at each x).
  const Evaluation& evaluate(const Eigen::VectorXd& x);

  Eigen::VectorXd start_point() const;

  // A constant added to the inner surface's integrals before the goal reads them: the moment-space
  // correction (docs/design.md "The written cavity", step 4), the written cavity's integrals less the
  // offset surface's. It does not depend on the variables, so no derivative changes.
  void set_inner_integral_shift(const Vector10d& shift);
  // The goal's margins (GoalSpec::margin, ::epsilon) for later solves: a correction aims a little
  // inside the user's margin, so the next contour's noise does not push the written solid out.
  void set_goal_margins(double margin, double epsilon);

  // New outer limits omax_i (#V, >= 0, the frame's units) for later evaluations: the optimiser
  // lowers them where the thickened surface folded (shape/shrink_outer_limit.h). The inward limit
  // and, in hard mode, the linear bounds follow.
  void set_outer_limit(const Eigen::VectorXd& limit);

  // The problem for the augmented Lagrangian; it refers to *this, which must outlive the solve.
  ConstrainedProblem constrained_problem();

 private:
  // all_integrals = false (the solver's own calls): only the integrals the goal reads are summed,
  // the others are NaN; every other output is the same as evaluate(x)'s, bit for bit.
  const Evaluation& evaluate_with_integrals(const Eigen::VectorXd& x, bool all_integrals);
  // Everything at x but what needs the projection onto Γ (objective_gradient and the Jacobians):
  // the offsets, surfaces, integrals, goal and objective; the integrals' per-vertex derivatives
  // stay in inner_jacobian_ / outer_jacobian_ (derivatives_pending_) for one projection to read.
  void evaluate_values(const Eigen::VectorXd& x, bool all_integrals);
  bool values_at(const Eigen::VectorXd& x, bool all_integrals) const;  // evaluate_values' cache holds x
  // objective_weight ∇f + Σ_r row_weights_r ∇row_r (rows: equalities, then inequalities) at x. The
  // rows and f read the same 20 integrals, so their weights are combined first and one row per
  // vertex (two with outer offsets) is projected onto Γ: O(#V·k) instead of O(R·#V·k) for R
  // integrals, and no per-row chain rule. Agrees with the Jacobians of evaluate(x) to rounding.
  void weighted_gradient(const Eigen::VectorXd& x, double objective_weight, const Eigen::VectorXd& row_weights,
                         Eigen::VectorXd& grad);
  // Columns [begin, end) of combined_: the face halves' derivative columns summed, weighted and
  // through the vertex's slopes (as fill_vertex_rows, but one weighted row), overshoot included.
  template <int Rows>
  void combine_vertex_rows(const Vector20d& weights, double objective_weight, Eigen::Index begin, Eigen::Index end);
  // Rows [vertex_split_[part], vertex_split_[part + 1]) of Γ c into `out` (#V).
  void apply_basis_part(const Eigen::VectorXd& coefficients, int part, Eigen::VectorXd& out) const;
  // Columns [begin, end) of a (rows by #V) matrix times the same rows of Γ: rows by k, one
  // part of the product (the parts add up to the whole).
  Eigen::MatrixXd project_rows(const Eigen::MatrixXd& per_vertex, Eigen::Index begin, Eigen::Index end) const;
  // Columns [begin, end) of per_vertex_'s Jacobian rows (Rows = integral_rows_ each: inner by Γα;
  // with outer offsets also inner by Γβ and outer by Γβ): the two face halves' columns added, times
  // the vertex's slope. Each entry (a + b) · slope, whatever Rows.
  template <int Rows>
  void fill_vertex_rows(Eigen::Index begin, Eigen::Index end);
  // The overshoot term is on (clamp mode with a weight), and its rows of per_vertex_ (by Γα, then
  // by Γβ) follow the integrals' Jacobian rows: R of them, 3R with outer offsets.
  bool has_overshoot_term() const { return options_.bounds == BoundsMode::clamp && options_.overshoot_weight > 0.0; }
  Eigen::Index first_overshoot_row() const { return options_.outer ? 3 * integral_rows_ : integral_rows_; }
  void run_parts(const std::function<void(int)>& part) const;  // part(0) and part(1), maybe on two threads
  void build_hard_bounds();
  void update_outer_inward_limit();

  Mesh mesh_;
  OffsetBand band_;
  Eigen::MatrixXd basis_;
  bool identity_basis_;
  int k_;
  GoalSpec goal_;
  int integral_rows_;                // goal_integral_rows(goal_)
  Eigen::Index goal_equality_count_;  // the goal's equality rows
  ReducedOptions options_;
  Vector10d fixed_outer_integrals_;  // the input's integrals, when there is no outer offset
  Vector10d inner_integral_shift_ = Vector10d::Zero();
  Eigen::VectorXd outer_inward_limit_;  // per vertex, see the constructor
  Eigen::MatrixXd hard_matrix_;      // hard mode: the linear block
  Eigen::VectorXd hard_lower_, hard_upper_;
  Evaluation cache_;
  // Work space of evaluate(), kept between calls.
  Vertices inner_vertices_, outer_vertices_;
  Faces face_parts_[2];              // the faces cut in two fixed halves
  Eigen::Index vertex_split_[3] = {0, 0, 0};  // vertex halves [split[p], split[p + 1])
  // integral_rows_ by #V, per face half; all +0 between evaluations (fill_vertex_rows clears them)
  Eigen::MatrixXd inner_jacobian_[2], outer_jacobian_[2];
  Eigen::MatrixXd per_vertex_;
  Eigen::VectorXd raw_inner_, raw_outer_;         // Γα and Γβ per vertex
  Eigen::VectorXd outer_slope_, inner_by_outer_;  // ∂δout/∂(Γβ) and ∂δin/∂(Γβ) per vertex
  Eigen::VectorXd overshoot_squares_;             // (raw − clamped)² per vertex (inner, outer)
  std::unique_ptr<WorkerPool> pool_;
  Eigen::MatrixXd combined_;          // 1 (2 with outer offsets) by #V: weighted_gradient's rows
  bool cache_valid_ = false;          // cache_ is complete (evaluate's) for cache_.x
  bool values_valid_ = false;         // cache_ has evaluate_values' outputs for cache_.x
  bool derivatives_pending_ = false;  // the per-vertex derivatives of cache_.x are unread (not +0)
  bool cache_all_integrals_ = false;  // the cached evaluation has all ten integrals
};

}  // namespace offsetopt
