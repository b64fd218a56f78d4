// The safeguards of the quadric void's moment-space correction (optimize/quadric_void.h): each
// round's Newton step comes from the first order of the boundary on the quadric, which misses what
// else moves with q. Where the void is thin, parts of it appear, vanish under the wall and are
// dropped as specks, and the boundary moves the goal's rows about twice as far as that first
// order says: the steps overshoot and the rounds oscillate (cgal-data_turbine floating at 0.8: void
// volumes 16% under the programme's, 16% over, 29% under, ... and no round within the float's
// tolerance in six). Two remedies, both reading only what the rounds measured:
// - the gain: a Newton step is divided by how far the rows moved, against how far its first order
//   said, on the last Newton step (least squares over the rows, clamped to [0.2, 5]);
// - the step back: a round that did not halve the best round's violation is replaced by a point of
//   the segment from the best round's quadric to its own, found by regula falsi on the row that was
//   furthest from met where that row changed sign, else halfway.
//
// Rows are the goal's at the aim (shape/goal.h): the equalities first (0 when met), then the
// inequalities (<= 0 when met).
#pragma once
#include <Eigen/Core>

#include "shape/goal.h"

namespace offsetopt {

// The equalities, then the inequalities, one vector.
Eigen::VectorXd goal_rows(const GoalValues& values);

// The rows' derivatives by the void's integrals (the inner half of the goal's Jacobians), rows as
// goal_rows orders them.
Eigen::MatrixXd goal_row_jacobian(const GoalValues& values);

// The norm of the equalities and of the violated inequalities; `equalities` leading rows are
// equalities.
double goal_violation(const Eigen::VectorXd& rows, Eigen::Index equalities);

// The fraction of the way from the best round (rows `best`) to the last (rows `now`) to try next:
// regula falsi on the row furthest from met at the best round when it changed sign (clamped to
// [0.1, 0.9]), else 0.5.
double step_back_fraction(const Eigen::VectorXd& best, const Eigen::VectorXd& now, Eigen::Index equalities);

// What the rows did (`before` → `after`) against what a step's first order predicted (`before` →
// `predicted`): the least-squares ratio, clamped to [0.2, 5]; 1 when nothing was predicted.
double observed_gain(const Eigen::VectorXd& before, const Eigen::VectorXd& predicted, const Eigen::VectorXd& after);

}  // namespace offsetopt
