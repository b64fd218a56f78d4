// Neumaier's compensated summation (Neumaier 1974, "Rundungsfehleranalyse einiger Verfahren zur
// Summation endlicher Summen"): the error of a long sum stays a few ulp of the result instead of
// growing with the number of terms and the cancellation between them. Terms are added in the
// caller's order, so the result is deterministic.
#pragma once
#include <cmath>

namespace offsetopt {

class NeumaierSum {
 public:
  void add(double term) {
    const double t = sum_ + term;
    if (std::fabs(sum_) >= std::fabs(term))
      compensation_ += (sum_ - t) + term;
    else
      compensation_ += (term - t) + sum_;
    sum_ = t;
  }
  double value() const { return sum_ + compensation_; }

 private:
  double sum_ = 0.0;
  double compensation_ = 0.0;
};

}  // namespace offsetopt
