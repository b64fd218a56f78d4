// The C1 clamp that holds the per-vertex offset bounds by construction (docs/design.md "Reduced
// problem"): instead of the paper's linear constraints δl <= Γk α <= δu (eq. 3), which have no
// feasible point on ordinary models with parts left solid, the offset actually applied is
//   δeff = smoothclamp(Γk α) into [lo, hi],
//   smoothclamp(x) = lo + sp(x - lo) - sp(x - hi),
//   sp(y) = 0 for y <= -τ,  (y + τ)^2 / (4τ) for |y| < τ,  y for y >= τ.
// sp is a C1 ramp (polynomial: no libm), so smoothclamp is C1, non-decreasing, equals x well
// inside the band and tends to lo / hi outside; its slope is in [0, 1]. With lo = hi the result
// is the constant lo (the part is left solid).
#pragma once
#include <Eigen/Core>

namespace offsetopt {

// Scalar form; `slope` receives d smoothclamp / dx when non-null, `slope_lo` d smoothclamp / d lo
// (in [0, 1]: how much a moving lower bound drags the result along). Requires lo <= hi, tau > 0.
double smooth_clamp(double x, double lo, double hi, double tau, double* slope = nullptr, double* slope_lo = nullptr);

// Element-wise over vectors of equal length; `slope` is resized and filled when non-null.
Eigen::VectorXd smooth_clamp(const Eigen::VectorXd& x, const Eigen::VectorXd& lo, const Eigen::VectorXd& hi,
                             double tau, Eigen::VectorXd* slope = nullptr);

}  // namespace offsetopt
