// The compact limited-memory BFGS matrix (R. H. Byrd, J. Nocedal, R. B. Schnabel,
// "Representations of quasi-Newton matrices and their use in limited memory methods",
// Math. Prog. 63, 1994), in the form used by L-BFGS-B (Byrd, Lu, Nocedal & Zhu, SIAM J. Sci.
// Comput. 16(5), 1995, section 3):
//
//   B = θ I − W M W^T,   W = [Y  θS]                       (n by 2p)
//   M = [[−D, L^T], [L, θ S^T S]]^{-1}                      (2p by 2p, symmetric, indefinite)
//
// S, Y are n by p, the last p corrections s_j = x_{j+1} − x_j, y_j = g_{j+1} − g_j, oldest
// first; D = diag(s_j^T y_j) > 0; L is the strictly lower triangle of S^T Y ((S^T Y)_{ij} for
// i > j); θ = y^T y / s^T y of the newest pair (1 while the memory is empty). B is the matrix
// obtained from θ I by p BFGS updates with the stored pairs, oldest first.
//
// M is applied through the factorisation of its inverse used by the Fortran code (routine bmv):
//   M^{-1} = [[D^½, 0], [−L D^−½, J]] · [[−D^½, D^−½ L^T], [0, J^T]],  J J^T = θ S^T S + L D^−1 L^T
// where the middle block is positive definite whenever every s_j^T y_j > 0, so a Cholesky
// factorisation that fails signals numerical trouble (the caller resets the memory).
#pragma once
#include <Eigen/Core>
#include <Eigen/Cholesky>

namespace offsetopt {

class LbfgsMemory {
 public:
  LbfgsMemory(int n, int capacity);

  void reset();
  // Stores (s, y), dropping the oldest pair when full, and refactorises. The caller has checked
  // s^T y > 0. Returns false (and resets the memory) if the middle matrix cannot be factorised.
  bool add(const Eigen::VectorXd& s, const Eigen::VectorXd& y);

  int size() const { return count_; }
  int capacity() const { return capacity_; }
  double theta() const { return theta_; }
  // W = [Y  θS], n by 2·size().
  const Eigen::MatrixXd& w() const { return w_; }
  // M, explicit, 2·size() by 2·size().
  const Eigen::MatrixXd& m() const { return m_; }
  // M^{-1} = [[−D, L^T], [L, θ S^T S]], 2·size() by 2·size().
  Eigen::MatrixXd middle_inverse() const;
  // M v through the factorisation (v of length 2·size()).
  Eigen::VectorXd apply_m(const Eigen::VectorXd& v) const;
  // θ I − W M W^T, n by n: for tests and diagnostics only.
  Eigen::MatrixXd dense_b() const;

 private:
  bool refactor();

  int n_;
  int capacity_;
  int count_ = 0;
  double theta_ = 1.0;
  Eigen::MatrixXd s_, y_;  // n by capacity, columns 0..count_-1 used, oldest first
  Eigen::MatrixXd sty_;    // count by count: S^T Y
  Eigen::MatrixXd sts_;    // count by count: S^T S
  Eigen::MatrixXd w_;      // n by 2·count
  Eigen::MatrixXd m_;      // 2·count by 2·count
  Eigen::LLT<Eigen::MatrixXd> j_factor_;
};

}  // namespace offsetopt
