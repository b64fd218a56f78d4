// Every eigenvalue of a small dense symmetric matrix H (n by n, both triangles stored) and, on
// demand, an approximate unit eigenvector (or a cluster's invariant subspace) with a proven bound
// on its distance from the true one. The Lanczos solver uses it to show cheaply that a step
// cannot have converged, so the full eigen-decomposition (every vector, by accumulated QR
// rotations: four to five times the work at the sizes of the demo meshes, n = 42..180) runs only
// where its vectors are used.
//
//  - Values: bit for bit those of Eigen's SelfAdjointEigenSolver(H) (the same scaling, the same
//    Householder tridiagonalisation and the same implicit QR sweeps on the tridiagonal; the sweeps
//    on the diagonal do not depend on whether rotations are accumulated), so every decision taken
//    on them is the one the full decomposition would take.
//  - Vectors: (block) inverse iteration on the tridiagonal (LU with partial pivoting, three
//    solves, orthonormalised), mapped back by the Householder reflections: O(n²) per vector.
//  - Bounds: with the residual r = ‖H V - V (VᵀHV)‖_F (recomputed from H) and the distance δ
//    from the eigenvalues of VᵀHV to the other computed eigenvalues, less their error,
//    ‖sin Θ(V, U)‖₂ ≤ r / δ (Davis–Kahan); a vector inside a cluster (δ ≤ 0) gets an infinite
//    bound, the cluster's subspace a finite one. The bound also covers the rounding of a
//    backward-stable dense solver's vector for the same eigenvalue (its angle is at most ε_H / δ,
//    ε_H = 4 n ε ‖H‖_F here), so for any quantity Lipschitz in the vector and invariant under
//    its sign, |f(z_dense) - f(z)| ≤ Lip(f) · (the bound).
#pragma once
#include <Eigen/Dense>

namespace offsetopt {

class ApproximateEigenpairs {
 public:
  // `H` n by n symmetric, n >= 1. Computes the values (and keeps the reduction for vectors).
  explicit ApproximateEigenpairs(const Eigen::MatrixXd& H);

  bool ok() const { return ok_; }  // false when the QR sweeps did not converge
  const Eigen::VectorXd& values() const { return values_; }  // n, descending
  // A unit approximation of the eigenvector of values()(i) (0 <= i < n) into z; returns the
  // distance bound (+inf when unproven). O(n²).
  double vector(int i, Eigen::VectorXd& z) const;
  // For a cluster, values()(first .. first + count - 1): an orthonormal basis V (n by count) of
  // an approximation of its invariant subspace; returns a bound on min over orthogonal Q of
  // ‖Z - V Q‖₂ for any orthonormal basis Z of the true subspace, or of a backward-stable dense
  // solver's vectors for these values (+inf when the cluster is not separated from the rest).
  // O(count n²).
  double subspace(int first, int count, Eigen::MatrixXd& V) const;

 private:
  Eigen::MatrixXd H_, reduced_;  // H; its Householder reduction (vectors below the subdiagonal)
  Eigen::VectorXd diagonal_, off_diagonal_, householder_, scaled_values_, values_;
  double slack_ = 0.0, tiny_ = 0.0;
  bool ok_ = false;
};

}  // namespace offsetopt
