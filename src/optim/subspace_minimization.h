// Subspace minimisation of L-BFGS-B by the direct primal method (Byrd, Lu, Nocedal & Zhu 1995,
// section 5.1), with the projection step of L-BFGS-B 3.0 (J. L. Morales and J. Nocedal,
// "Remark on Algorithm 778", ACM TOMS 38(1), 2011).
//
// With Z the free variables at the Cauchy point x^c, the reduced model is minimised over them:
//   r̂ = Z^T (g + θ (x^c − x) − W M c)                      reduced gradient at x^c
//   B̂ = θ I − W_Z M W_Z^T,  W_Z = Z^T W                    reduced Hessian (#free by #free)
//   d̂ = −B̂^{-1} r̂ = −r̂/θ − W_Z K^{-1} W_Z^T r̂ / θ²,    K = M^{-1} − W_Z^T W_Z / θ  (2p by 2p)
// (Sherman–Morrison–Woodbury; K is nonsingular whenever B̂ is positive definite and is solved by
// LU with full pivoting). The step is then the projection P(x^c + d̂) if that is a descent
// direction from x (v3.0), otherwise x^c + α* d̂ with α* ≤ 1 the largest step keeping the free
// variables feasible (the original paper).
#pragma once
#include <Eigen/Core>

#include "optim/cauchy_point.h"
#include "optim/lbfgs_memory.h"

namespace offsetopt {

struct SubspaceStep {
  bool ok = true;             // false: K was numerically singular (reset the memory)
  Eigen::VectorXd x_bar;      // the new trial point, inside the box (n)
  Eigen::VectorXd direction;  // d̂ on the free variables (#free), before projection/truncation
  bool projected = false;     // the v3.0 projection was used
  double truncation = 1.0;    // α* when the truncated step was used
};

// With an empty memory or no free variables x_bar = x^c.
SubspaceStep subspace_minimization(const Eigen::VectorXd& x, const Eigen::VectorXd& g,
                                   const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                   const LbfgsMemory& memory, const CauchyPoint& cauchy);

}  // namespace offsetopt
