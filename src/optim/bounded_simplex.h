// A linear programme with few rows and many bounded columns, solved by a bounded-variable revised
// primal simplex (Dantzig 1963; Chvátal 1983, ch. 8; Koberstein 2005 for the bound flips):
//
//   maximise cᵀx  subject to  a_iᵀx (≤ | = | ≥) b_i  (i < m),   l ≤ x ≤ u  (±∞ allowed).
//
// Shapes: A is m × n, column-major (one column per variable: the many cells of
// cavity/reachability.h), b has m entries, c, l, u have n. Free and one-sided columns are allowed
// (they are few: a margin variable); the work is O(m·n) per pricing pass and O(m²) per pivot, so
// m should stay small (≲ 100) while n may be 10⁴–10⁶.
//
// Each row i gets a slack s_i (a_iᵀx + s_i = b_i, s_i ≥ 0 for ≤, ≤ 0 for ≥, = 0 for =) and, where
// the start violates it, an artificial; phase 1 maximises −Σ artificials. The basis inverse is
// kept dense (m × m), updated by rank-one pivots and refactorised every `refactor_every` pivots.
// Pricing visits every column in index order; the attractive ones are tried in decreasing
// |reduced cost| (ties to the lower index), and while a step is only a bound flip (the entering
// column reaches its other bound first) the duals do not change, so the next candidate is tried
// without pricing again: a column that goes from 0 to 1 costs O(m²), not a pass. The ratio test is
// Harris's two-pass test; after `degenerate_before_bland` degenerate pivots in a row the rule
// becomes Bland's (lowest index enters and leaves) until a step makes progress, so it cannot cycle.
//
// Signs of the results (a maximisation): at the optimum the row duals y = B⁻ᵀc_B satisfy
// y_i ≥ 0 on ≤ rows and y_i ≤ 0 on ≥ rows, and c_j − yᵀA_j ≤ 0 where x_j = l_j, ≥ 0 where
// x_j = u_j. When infeasible, y is a Farkas certificate with the same sign pattern: Aᵀy vanishes on
// free columns and min over the box of (Aᵀy)ᵀx > yᵀb, which no feasible x allows
// (farkas_gap evaluates it).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace offsetopt {

enum class RowSense { less_equal, equal, greater_equal };

enum class LpStatus { optimal, infeasible, unbounded, iteration_cap, numerical };
const char* to_string(LpStatus status);

struct LinearProgram {
  Eigen::MatrixXd A;             // m × n, column-major
  Eigen::VectorXd b;             // m
  std::vector<RowSense> sense;   // m
  Eigen::VectorXd c;             // n, maximised
  Eigen::VectorXd lower, upper;  // n; -inf / +inf for a missing bound, lower <= upper
};

struct BoundedSimplexOptions {
  int max_iterations = 200000;          // pivots plus bound flips, both phases
  int refactor_every = 50;              // pivots between refactorisations of the basis
  double feasibility_tolerance = 1e-9;  // absolute, on rows and bounds (scale the rows to O(1))
  double optimality_tolerance = 1e-9;   // absolute, on reduced costs
  double pivot_tolerance = 1e-9;        // smallest |α| a ratio test may pivot on
  int degenerate_before_bland = 30;
  // Try the dual simplex with bound flips first (from the slack basis, every column on the bound
  // its cost favours), then confirm with the primal phase 2; the primal method from `start` when
  // it gives up. Far fewer passes when the optimum moves many columns between their bounds.
  bool dual = false;

  static BoundedSimplexOptions defaults() { return BoundedSimplexOptions(); }
  // Empty when valid, else what is wrong.
  std::string check() const;
};

struct LpResult {
  LpStatus status = LpStatus::numerical;
  Eigen::VectorXd x;          // n: the best iterate (the optimum when optimal)
  Eigen::VectorXd y;          // m: row duals (optimal) or the Farkas certificate (infeasible)
  double objective = 0.0;     // cᵀx
  int iterations = 0;         // pivots and bound flips, both phases
  int phase1_iterations = 0;
  int pricing_passes = 0;
  std::string message;        // what went wrong, when not optimal
  // The final basis, one variable per row (optimal only, else empty): j < n a column, n + i the
  // slack of row i. Handed to the next, neighbouring programme as `start_basis`.
  std::vector<int> basis;
};

// `start` (optional, n entries): 1 starts a column at its upper bound, 0 at its lower bound (a
// warm start from a neighbouring programme); free columns start at 0 whatever it says.
// `start_basis` (optional, m distinct variables as LpResult::basis numbers them; dual method
// only): the dual method starts from this basis instead of the slack basis, every nonbasic column
// put on the bound its reduced cost favours (`start` breaks ties). A programme whose data moved a
// little from the one that ended on that basis (a Dinkelbach step, a block split) is then a few
// pivots from its optimum, where from the slack basis the duals start at 0 and every column is
// flipped on the way. A singular or malformed basis falls back to the slack basis.
LpResult bounded_simplex(const LinearProgram& lp, const BoundedSimplexOptions& options = {},
                         const std::vector<std::int8_t>* start = nullptr, const std::vector<int>* start_basis = nullptr);

// min over the box of (Aᵀy)ᵀx − yᵀb, with y's signs checked (−inf when a sign is wrong or Aᵀy
// is non-zero on an unbounded side): positive proves the rows infeasible.
double farkas_gap(const LinearProgram& lp, const Eigen::VectorXd& y);

}  // namespace offsetopt
