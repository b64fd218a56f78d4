// The Moré–Thuente line search (J. J. Moré and D. J. Thuente, "Line search algorithms with
// guaranteed sufficient decrease", ACM TOMS 20(3), 1994), following MINPACK-2's dcsrch/dcstep,
// which is the line search of L-BFGS-B. It finds a step stp > 0 along a descent direction with
//   φ(stp) ≤ φ(0) + ftol·stp·φ'(0)        (sufficient decrease)
//   |φ'(stp)| ≤ gtol·|φ'(0)|              (curvature: together, the strong Wolfe conditions)
// where φ(stp) = f(x + stp·d) and φ'(0) < 0.
//
// Reverse communication: start() and advance() return evaluate with step() set to the next trial;
// the caller evaluates φ and φ' there and calls advance(). Any other state ends the search.
// Deviation from MINPACK-2: square roots of cubic-interpolation discriminants are taken of
// max(0, ·), so rounding can never produce a NaN step.
#pragma once
#include <string>

namespace offsetopt {

struct MoreThuenteOptions {
  double ftol = 1e-3;  // sufficient-decrease constant μ, in (0, gtol) for the strong Wolfe pair
  double gtol = 0.9;   // curvature constant η, in (ftol, 1)
  double xtol = 0.1;   // relative width of the bracketing interval below which the search stops
  double stpmin = 0.0;
  double stpmax = 1e10;

  // Empty when valid, else what is wrong (one line). start() returns Error for these and for a
  // bad first step or slope.
  std::string check() const;
};

enum class MoreThuenteStatus {
  evaluate,                 // evaluate φ, φ' at step() and call advance()
  converged,                // the strong Wolfe conditions hold at the last evaluated step
  warning_rounding_errors,  // the bracket cannot shrink any more: rounding prevents progress
  warning_xtol,             // the bracket is narrower than xtol·stmax
  warning_stpmax,           // the step is stpmax and sufficient decrease holds with φ' < 0
  warning_stpmin,           // the step is stpmin and sufficient decrease or curvature fails
  error                     // bad input: φ'(0) ≥ 0, stp outside [stpmin, stpmax], bad constants
};

class MoreThuenteSearch {
 public:
  // φ(0) = f0, φ'(0) = g0 (must be < 0), first trial step stp.
  MoreThuenteStatus start(double f0, double g0, double stp, const MoreThuenteOptions& settings);
  // φ and φ' at the step last returned by step().
  MoreThuenteStatus advance(double f, double g);
  double step() const { return stp_; }

 private:
  MoreThuenteOptions s_;
  double stp_ = 0.0;
  bool brackt_ = false;
  int stage_ = 1;
  double finit_ = 0.0, ginit_ = 0.0, gtest_ = 0.0, width_ = 0.0, width1_ = 0.0;
  double stx_ = 0.0, fx_ = 0.0, gx_ = 0.0;
  double sty_ = 0.0, fy_ = 0.0, gy_ = 0.0;
  double stmin_ = 0.0, stmax_ = 0.0;
};

// One safeguarded step of the interval update (MINPACK-2 dcstep): given the best step stx, the
// other end sty and the trial stp (with function values and derivatives), updates the interval
// and returns the new trial step in stp. Exposed for testing.
void more_thuente_step(double& stx, double& fx, double& dx, double& sty, double& fy, double& dy,
                       double& stp, double fp, double dp, bool& brackt, double stpmin,
                       double stpmax);

}  // namespace offsetopt
