// The generalised Cauchy point of L-BFGS-B (Byrd, Lu, Nocedal & Zhu 1995, section 4,
// Algorithm CP): the first local minimiser of the quadratic model
//   m(z) = g^T (z − x) + ½ (z − x)^T B (z − x),   B = θ I − W M W^T  (optim/lbfgs_memory.h)
// along the projected steepest-descent path z(t) = P(x − t g), P the projection onto the box
// lower ≤ z ≤ upper (infinite entries allowed). The path is piecewise linear with a breakpoint
// per variable (t_i = (x_i − u_i)/g_i for g_i < 0, (x_i − l_i)/g_i for g_i > 0); the segments are
// visited in increasing t (ties by index) and the model's slope f' and curvature f'' are updated
// in O(p²) per breakpoint, f'' safeguarded below by ε·f''_0 as in the Fortran code (v3.0).
#pragma once
#include <vector>

#include <Eigen/Core>

#include "optim/lbfgs_memory.h"

namespace offsetopt {

struct CauchyPoint {
  Eigen::VectorXd x;      // x^c, inside the box (n)
  Eigen::VectorXd c;      // W^T (x^c − x) (2p)
  std::vector<int> free;  // variables not fixed at a bound at x^c, ascending
  int breakpoints = 0;    // segments passed before the minimiser
};

// x must lie in the box; lower ≤ upper. Variables with lower == upper are always fixed; a
// variable sitting on a bound with the gradient pushing it outwards (or zero) is fixed from the
// start, as in the Fortran code.
CauchyPoint generalized_cauchy_point(const Eigen::VectorXd& x, const Eigen::VectorXd& g,
                                     const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                     const LbfgsMemory& memory);

}  // namespace offsetopt
