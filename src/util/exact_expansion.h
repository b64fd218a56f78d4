// Exact arithmetic on doubles for the orientation predicates (Shewchuk 1997, "Adaptive Precision
// Floating-Point Arithmetic and Fast Robust Geometric Predicates"): error-free transformations
// (Knuth's TwoSum, Dekker's TwoProduct with Veltkamp's split), exact because -ffp-contract=off
// keeps every operation separately rounded, and Grow-Expansion.
#pragma once
#include <array>
#include <cstddef>

namespace offsetopt {

inline void two_sum(double a, double b, double& sum, double& error) {
  sum = a + b;
  const double b_virtual = sum - a;
  const double a_virtual = sum - b_virtual;
  error = (a - a_virtual) + (b - b_virtual);
}

inline void split(double a, double& hi, double& lo) {
  const double c = 134217729.0 * a;  // 2^27 + 1
  const double a_big = c - a;
  hi = c - a_big;
  lo = a - hi;
}

inline void two_product(double a, double b, double& product, double& error) {
  product = a * b;
  double ahi, alo, bhi, blo;
  split(a, ahi, alo);
  split(b, bhi, blo);
  error = ((ahi * bhi - product) + ahi * blo + alo * bhi) + alo * blo;
}

// Adds `term` to a nonoverlapping expansion sorted by increasing magnitude; the expansion stays
// exact and nonoverlapping. `e` needs room for length + 1 terms.
template <std::size_t N>
void grow_expansion(std::array<double, N>& e, std::size_t& length, double term) {
  double q = term;
  for (std::size_t i = 0; i < length; ++i) {
    double sum, error;
    two_sum(q, e[i], sum, error);
    e[i] = error;
    q = sum;
  }
  e[length++] = q;
}

}  // namespace offsetopt
