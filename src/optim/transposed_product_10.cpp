#include "optim/transposed_product_10.h"

namespace offsetopt {

void transposed_product_10(const Eigen::Matrix<double, 10, Eigen::Dynamic>& C, const Eigen::Matrix<double, 10, 1>& x, double* out) {
  // Both are 16-byte aligned two by two (80-byte columns from an aligned start).
  using Pair = Eigen::Map<const Eigen::Array2d, Eigen::Aligned16>;
  const Eigen::Array2d x0 = Pair(x.data()), x1 = Pair(x.data() + 2), x2 = Pair(x.data() + 4), x3 = Pair(x.data() + 6),
                       x4 = Pair(x.data() + 8);
  for (Eigen::Index k = 0; k < C.cols(); ++k) {
    const double* c = C.col(k).data();
    Eigen::Array2d sum = Eigen::Array2d::Zero();
    sum += Pair(c) * x0;
    sum += Pair(c + 2) * x1;
    sum += Pair(c + 4) * x2;
    sum += Pair(c + 6) * x3;
    sum += Pair(c + 8) * x4;
    out[k] = 0.0 + (sum[0] + sum[1]);
  }
}

}  // namespace offsetopt
