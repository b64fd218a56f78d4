#include "geometry/intrinsic_mollification.h"

#include <algorithm>
#include <cmath>

namespace offsetopt {

Eigen::Matrix<double, Eigen::Dynamic, 3> face_edge_lengths(const Vertices& V, const Faces& F) {
  Eigen::Matrix<double, Eigen::Dynamic, 3> lengths(F.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Eigen::RowVector3d e = V.row(F(f, (k + 2) % 3)) - V.row(F(f, (k + 1) % 3));
      lengths(f, k) = std::sqrt(e.squaredNorm());
    }
  return lengths;
}

Mollification intrinsic_mollification(const Eigen::Matrix<double, Eigen::Dynamic, 3>& lengths, double relative_margin) {
  Mollification out;
  if (!(relative_margin > 0.0) || lengths.rows() == 0) return out;
  double sum = 0.0;  // face order, then corner order: a fixed summation order
  for (Eigen::Index f = 0; f < lengths.rows(); ++f)
    for (int k = 0; k < 3; ++k) sum += lengths(f, k);
  const double mean = sum / static_cast<double>(3 * lengths.rows());
  out.delta = relative_margin * mean;
  if (!(out.delta > 0.0) || !std::isfinite(out.delta)) {
    out.delta = 0.0;
    return out;
  }
  for (Eigen::Index f = 0; f < lengths.rows(); ++f) {
    bool below = false;
    for (int i = 0; i < 3; ++i) {
      const double slack = lengths(f, (i + 1) % 3) + lengths(f, (i + 2) % 3) - lengths(f, i);
      if (slack < out.delta) {
        below = true;
        out.epsilon = std::max(out.epsilon, out.delta - slack);
      }
    }
    if (below) ++out.faces_below_margin;
  }
  return out;
}

double intrinsic_area(double a, double b, double c) {
  // Sort so that a >= b >= c; then every factor below is computed without cancellation.
  if (a < b) std::swap(a, b);
  if (b < c) std::swap(b, c);
  if (a < b) std::swap(a, b);
  const double product = (a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c));
  return product > 0.0 ? 0.25 * std::sqrt(product) : 0.0;
}

}  // namespace offsetopt
