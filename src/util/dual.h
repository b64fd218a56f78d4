// Forward-mode automatic differentiation with a fixed number N of partial derivatives, for the
// small closed-form goal functions of the optimiser (a few dozen operations on the 10 + 10 volume
// integrals of the outer and inner surfaces). Exact derivatives, no step size; only +, -, *, /
// and sqrt, so results are as deterministic as the plain arithmetic.
#pragma once
#include <array>
#include <cmath>

namespace offsetopt {

template <int N>
struct Dual {
  double value = 0.0;
  std::array<double, N> grad{};  // d value / d input_j

  Dual() = default;
  Dual(double v) : value(v) {}  // NOLINT: constants convert implicitly

  // The j-th independent variable with value v.
  static Dual variable(double v, int j) {
    Dual d(v);
    d.grad[static_cast<std::size_t>(j)] = 1.0;
    return d;
  }
};

template <int N>
Dual<N> operator+(const Dual<N>& a, const Dual<N>& b) {
  Dual<N> r(a.value + b.value);
  for (int j = 0; j < N; ++j) r.grad[j] = a.grad[j] + b.grad[j];
  return r;
}
template <int N>
Dual<N> operator-(const Dual<N>& a, const Dual<N>& b) {
  Dual<N> r(a.value - b.value);
  for (int j = 0; j < N; ++j) r.grad[j] = a.grad[j] - b.grad[j];
  return r;
}
template <int N>
Dual<N> operator-(const Dual<N>& a) {
  Dual<N> r(-a.value);
  for (int j = 0; j < N; ++j) r.grad[j] = -a.grad[j];
  return r;
}
template <int N>
Dual<N> operator*(const Dual<N>& a, const Dual<N>& b) {
  Dual<N> r(a.value * b.value);
  for (int j = 0; j < N; ++j) r.grad[j] = a.grad[j] * b.value + a.value * b.grad[j];
  return r;
}
template <int N>
Dual<N> operator/(const Dual<N>& a, const Dual<N>& b) {
  const double inv = 1.0 / b.value;
  Dual<N> r(a.value * inv);
  for (int j = 0; j < N; ++j) r.grad[j] = (a.grad[j] - r.value * b.grad[j]) * inv;
  return r;
}
template <int N>
Dual<N> operator+(const Dual<N>& a, double b) { return a + Dual<N>(b); }
template <int N>
Dual<N> operator+(double a, const Dual<N>& b) { return Dual<N>(a) + b; }
template <int N>
Dual<N> operator-(const Dual<N>& a, double b) { return a - Dual<N>(b); }
template <int N>
Dual<N> operator-(double a, const Dual<N>& b) { return Dual<N>(a) - b; }
template <int N>
Dual<N> operator*(const Dual<N>& a, double b) {
  Dual<N> r(a.value * b);
  for (int j = 0; j < N; ++j) r.grad[j] = a.grad[j] * b;
  return r;
}
template <int N>
Dual<N> operator*(double a, const Dual<N>& b) { return b * a; }
template <int N>
Dual<N> operator/(const Dual<N>& a, double b) { return a / Dual<N>(b); }
template <int N>
Dual<N> operator/(double a, const Dual<N>& b) { return Dual<N>(a) / b; }

template <int N>
Dual<N> sqrt(const Dual<N>& a) {
  const double s = std::sqrt(a.value);
  Dual<N> r(s);
  const double scale = s > 0.0 ? 0.5 / s : 0.0;  // the derivative at 0 is taken as 0, not inf
  for (int j = 0; j < N; ++j) r.grad[j] = a.grad[j] * scale;
  return r;
}

inline double sqrt_value(double x) { return std::sqrt(x); }
template <int N>
double value_of(const Dual<N>& a) { return a.value; }
inline double value_of(double a) { return a; }

}  // namespace offsetopt
