#include "optim/more_thuente.h"

#include <algorithm>
#include <cmath>

namespace offsetopt {

namespace {

double max3(double a, double b, double c) { return std::max(a, std::max(b, c)); }

// s·sqrt(max(0, (θ/s)² − (a/s)(b/s))): the scaled square root of the cubic's discriminant.
double scaled_root(double s, double theta, double a, double b) {
  const double t = theta / s;
  const double disc = t * t - (a / s) * (b / s);
  return s * std::sqrt(std::max(0.0, disc));
}

// The cubic through (stp, fp, dp) and (st, f, d): its minimiser is stp + r·(st − stp); returns
// r (cases 2 and 4 below; the end point is stx or sty). (f − fp)/(stp − st) is computed as case 4
// always wrote it, (fp − f)/(st − stp): negating both differences is exact, so the bits are the
// same either way.
double cubic_step_ratio(double stp, double fp, double dp, double st, double f, double d) {
  const double theta = 3.0 * (fp - f) / (st - stp) + d + dp;
  const double s = max3(std::fabs(theta), std::fabs(d), std::fabs(dp));
  double gamma = scaled_root(s, theta, d, dp);
  if (stp > st) gamma = -gamma;
  const double p = (gamma - dp) + theta;
  const double q = ((gamma - dp) + gamma) + d;
  return p / q;
}

}  // namespace

void more_thuente_step(double& stx, double& fx, double& dx, double& sty, double& fy, double& dy,
                       double& stp, double fp, double dp, bool& brackt, double stpmin,
                       double stpmax) {
  const double sgnd = dp * (dx / std::fabs(dx));
  double stpf;

  if (fp > fx) {
    // Case 1: higher function value. The minimum is bracketed; take the cubic step if it is
    // closer to stx than the quadratic step, else their average.
    const double theta = 3.0 * (fx - fp) / (stp - stx) + dx + dp;
    const double s = max3(std::fabs(theta), std::fabs(dx), std::fabs(dp));
    double gamma = scaled_root(s, theta, dx, dp);
    if (stp < stx) gamma = -gamma;
    const double p = (gamma - dx) + theta;
    const double q = ((gamma - dx) + gamma) + dp;
    const double r = p / q;
    const double stpc = stx + r * (stp - stx);
    const double stpq = stx + ((dx / ((fx - fp) / (stp - stx) + dx)) / 2.0) * (stp - stx);
    if (std::fabs(stpc - stx) < std::fabs(stpq - stx)) {
      stpf = stpc;
    } else {
      stpf = stpc + (stpq - stpc) / 2.0;
    }
    brackt = true;
  } else if (sgnd < 0.0) {
    // Case 2: lower function value and derivatives of opposite sign: bracketed; take the cubic
    // step if it is farther from stp than the secant step, else the secant step.
    const double stpc = stp + cubic_step_ratio(stp, fp, dp, stx, fx, dx) * (stx - stp);
    const double stpq = stp + (dp / (dp - dx)) * (stx - stp);
    if (std::fabs(stpc - stp) > std::fabs(stpq - stp)) {
      stpf = stpc;
    } else {
      stpf = stpq;
    }
    brackt = true;
  } else if (std::fabs(dp) < std::fabs(dx)) {
    // Case 3: lower function value, derivatives of the same sign, and the magnitude of the
    // derivative decreases. The cubic step is used only if the cubic tends to infinity in the
    // direction of the step or its minimum is beyond stp; otherwise the step is set to the
    // relevant end of the allowed range.
    const double theta = 3.0 * (fx - fp) / (stp - stx) + dx + dp;
    const double s = max3(std::fabs(theta), std::fabs(dx), std::fabs(dp));
    double gamma = scaled_root(s, theta, dx, dp);
    if (stp > stx) gamma = -gamma;
    const double p = (gamma - dp) + theta;
    const double q = (gamma + (dx - dp)) + gamma;
    const double r = p / q;
    double stpc;
    if (r < 0.0 && gamma != 0.0) {
      stpc = stp + r * (stx - stp);
    } else if (stp > stx) {
      stpc = stpmax;
    } else {
      stpc = stpmin;
    }
    const double stpq = stp + (dp / (dp - dx)) * (stx - stp);
    if (brackt) {
      // A minimiser has been bracketed: take the step closer to stp, but not too close to sty.
      stpf = (std::fabs(stpc - stp) < std::fabs(stpq - stp)) ? stpc : stpq;
      if (stp > stx) {
        stpf = std::min(stp + 0.66 * (sty - stp), stpf);
      } else {
        stpf = std::max(stp + 0.66 * (sty - stp), stpf);
      }
    } else {
      // Not bracketed: take the step farther from stp, within [stpmin, stpmax].
      stpf = (std::fabs(stpc - stp) > std::fabs(stpq - stp)) ? stpc : stpq;
      stpf = std::min(stpmax, stpf);
      stpf = std::max(stpmin, stpf);
    }
  } else {
    // Case 4: lower function value, derivatives of the same sign, and the magnitude of the
    // derivative does not decrease. Without a bracket the step goes to stpmin or stpmax.
    if (brackt) {
      stpf = stp + cubic_step_ratio(stp, fp, dp, sty, fy, dy) * (sty - stp);
    } else if (stp > stx) {
      stpf = stpmax;
    } else {
      stpf = stpmin;
    }
  }

  // Update the interval that contains a minimiser.
  if (fp > fx) {
    sty = stp;
    fy = fp;
    dy = dp;
  } else {
    if (sgnd < 0.0) {
      sty = stx;
      fy = fx;
      dy = dx;
    }
    stx = stp;
    fx = fp;
    dx = dp;
  }
  stp = stpf;
}

std::string MoreThuenteOptions::check() const {
  if (!(ftol >= 0.0)) return "ftol must be >= 0";
  if (!(gtol >= 0.0)) return "gtol must be >= 0";
  if (!(xtol >= 0.0)) return "xtol must be >= 0";
  if (!(stpmin >= 0.0)) return "stpmin must be >= 0";
  if (!(stpmax >= stpmin)) return "stpmax must be >= stpmin";
  return std::string();
}

MoreThuenteStatus MoreThuenteSearch::start(double f0, double g0, double stp,
                                          const MoreThuenteOptions& settings) {
  s_ = settings;
  stp_ = stp;
  if (!(stp >= s_.stpmin) || !(stp <= s_.stpmax) || !(g0 < 0.0) || !s_.check().empty() || !std::isfinite(f0)) {
    return MoreThuenteStatus::error;
  }
  brackt_ = false;
  stage_ = 1;
  finit_ = f0;
  ginit_ = g0;
  gtest_ = s_.ftol * ginit_;
  width_ = s_.stpmax - s_.stpmin;
  width1_ = width_ / 0.5;
  stx_ = 0.0;
  fx_ = finit_;
  gx_ = ginit_;
  sty_ = 0.0;
  fy_ = finit_;
  gy_ = ginit_;
  stmin_ = 0.0;
  stmax_ = stp_ + 4.0 * stp_;
  return MoreThuenteStatus::evaluate;
}

MoreThuenteStatus MoreThuenteSearch::advance(double f, double g) {
  constexpr double kExtrapolateLower = 1.1;
  constexpr double kExtrapolateUpper = 4.0;

  const double ftest = finit_ + stp_ * gtest_;
  if (stage_ == 1 && f <= ftest && g >= 0.0) stage_ = 2;

  // Tests for warnings, then for convergence.
  MoreThuenteStatus state = MoreThuenteStatus::evaluate;
  if (brackt_ && (stp_ <= stmin_ || stp_ >= stmax_)) state = MoreThuenteStatus::warning_rounding_errors;
  if (brackt_ && stmax_ - stmin_ <= s_.xtol * stmax_) state = MoreThuenteStatus::warning_xtol;
  if (stp_ == s_.stpmax && f <= ftest && g <= gtest_) state = MoreThuenteStatus::warning_stpmax;
  if (stp_ == s_.stpmin && (f > ftest || g >= gtest_)) state = MoreThuenteStatus::warning_stpmin;
  if (f <= ftest && std::fabs(g) <= s_.gtol * (-ginit_)) state = MoreThuenteStatus::converged;
  if (state != MoreThuenteStatus::evaluate) return state;

  if (stage_ == 1 && f <= fx_ && f > ftest) {
    // In the first stage, with a lower value that lacks sufficient decrease, work with the
    // modified function ψ(stp) = φ(stp) − φ(0) − ftol·stp·φ'(0).
    double fm = f - stp_ * gtest_;
    double fxm = fx_ - stx_ * gtest_;
    double fym = fy_ - sty_ * gtest_;
    double gm = g - gtest_;
    double gxm = gx_ - gtest_;
    double gym = gy_ - gtest_;
    more_thuente_step(stx_, fxm, gxm, sty_, fym, gym, stp_, fm, gm, brackt_, stmin_, stmax_);
    fx_ = fxm + stx_ * gtest_;
    fy_ = fym + sty_ * gtest_;
    gx_ = gxm + gtest_;
    gy_ = gym + gtest_;
  } else {
    more_thuente_step(stx_, fx_, gx_, sty_, fy_, gy_, stp_, f, g, brackt_, stmin_, stmax_);
  }

  // Force a sufficient decrease in the size of the bracketing interval.
  if (brackt_) {
    if (std::fabs(sty_ - stx_) >= 0.66 * width1_) stp_ = stx_ + 0.5 * (sty_ - stx_);
    width1_ = width_;
    width_ = std::fabs(sty_ - stx_);
  }

  // The interval of allowed steps.
  if (brackt_) {
    stmin_ = std::min(stx_, sty_);
    stmax_ = std::max(stx_, sty_);
  } else {
    stmin_ = stp_ + kExtrapolateLower * (stp_ - stx_);
    stmax_ = stp_ + kExtrapolateUpper * (stp_ - stx_);
  }

  stp_ = std::max(stp_, s_.stpmin);
  stp_ = std::min(stp_, s_.stpmax);

  // If further progress is not possible, let stp be the best point obtained so far.
  if ((brackt_ && (stp_ <= stmin_ || stp_ >= stmax_)) ||
      (brackt_ && stmax_ - stmin_ <= s_.xtol * stmax_)) {
    stp_ = stx_;
  }
  return MoreThuenteStatus::evaluate;
}

}  // namespace offsetopt
