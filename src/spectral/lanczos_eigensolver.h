// The k smallest eigenpairs of a graph/mesh Laplacian: L φ = λ M φ with L symmetric positive
// semi-definite (#V by #V, e.g. geometry/cotan_laplacian.h) and M diagonal positive (the lumped
// mass of geometry/lumped_mass.h), or L φ = λ φ when no mass is given (the paper's choice,
// Musialski et al. 2015 section 5.1; Vallet & Lévy 2008 for the generalised form).
//
// Method: block Krylov–Schur (thick-restart block Lanczos; Stewart 2001, Zhou & Saad 2008) with
// full re-orthogonalisation (classical Gram–Schmidt twice against the whole basis) on the
// shift-inverted operator D (L + sM)⁻¹ D, D = M^(1/2) (spectral/shift_invert_operator.h), whose
// largest eigenvalues θ = 1/(λ + s) are the wanted smallest λ.
//  - Shift: L is singular (constants are in its null space), so the pole sits at -s < 0:
//    s = shift_scale · tr(L) / (#V · tr(M)). On a sphere that is about λ₂/7, small enough not to
//    slow convergence (the rate depends on (λ_{k+1} - λ_k)/(λ_k + s)) and large enough that the
//    LDLᵀ pivots stay clear of zero. It scales like λ, so scaled copies of a mesh behave alike.
//  - Start: a block of `block_size` vectors from Rng(seed). A block start finds every copy of a
//    repeated eigenvalue up to the block size (single-vector Lanczos, e.g. ARPACK, can miss one).
//  - Convergence: Ritz pair i is accepted when its estimated relative residual
//    ‖Op y - θ y‖ / θ is below the tolerance; pairs far below it are locked (their coupling to
//    the rest is dropped). The solver keeps going until the first k pairs, every further pair in
//    the same cluster as the k-th (relative gap below cluster_tolerance), and the first pair past
//    that cluster are converged, so a cluster straddling k is complete and its end is known.
//    Then the true residuals are computed; should one miss the tolerance the internal tolerance
//    is tightened and the iteration continues.
//    A step's full Rayleigh–Ritz (every Ritz vector, by Eigen's dense solver) runs only where the
//    test might pass or a restart needs the vectors; elsewhere the step is shown unconverged from
//    the same Ritz values (bit for bit) and a few approximate Ritz vectors with proven error
//    bounds (spectral/approximate_eigenpairs.h), so the results are the same bits either way.
//  - Small problems (a Krylov basis would be a large part of #V) are solved densely with Eigen's
//    SelfAdjointEigenSolver on M^(-1/2) L M^(-1/2) instead; the result is reported the same way.
//
// Output: eigenvalues ascending (Rayleigh quotients φᵀLφ / φᵀMφ); eigenvectors normalised
// (‖φ‖₂ = 1 for the standard problem, φᵀMφ = 1 for the generalised one), sign fixed so the entry
// of largest magnitude (first such index) is positive; residuals ‖Lφ - λMφ‖₂ / (‖L‖∞ ‖φ‖₂).
// Deterministic: the same input gives the same bits on every x86-64 machine.
#pragma once
#include <Eigen/Sparse>
#include <cstdint>
#include <functional>
#include <string>

#include "mesh/mesh.h"

namespace offsetopt {

struct LanczosOptions {
  // converged when every returned pair has ‖Lφ - λMφ‖₂ ≤ tolerance · ‖L‖∞ · ‖φ‖₂.
  double tolerance = 1e-10;
  // Vectors per Lanczos block. At least the largest multiplicity expected (icosahedral symmetry
  // gives 5, octahedral 3, rotational 2); larger blocks make the triangular solves faster per
  // vector but need more vectors to converge (measured for k = 36: 6 is fastest).
  int block_size = 6;
  // Krylov basis size before a thick restart; 0 means max(3k, k + 24·block_size), enough that
  // k = 36 converges without a restart (restarts cost a rotation of the whole basis). The basis
  // is allocated as it grows.
  int max_basis = 0;
  // Cap on operator applications (vectors through (L + sM)⁻¹); 0 means 200 · (k + block_size).
  long max_operator_applications = 0;
  // s = shift_scale · tr(L) / (#V · tr(M)); see above.
  double shift_scale = 1.0;
  // Ritz values closer than this (relative to λ + s) count as one cluster.
  double cluster_tolerance = 1e-3;
  // Seed of the start block.
  std::uint64_t seed = 0x5eed2015ull;
  // Use the dense solver when #V is at most this (or when the basis would exceed #V / 3).
  int dense_below = 200;
  // Threads for the iteration (triangular solves, projections); 0 means min(2, cores). The
  // results are bit for bit the same for any number (fixed partitions, no shared sums).
  int threads = 0;
  // Observer of the iteration (a progress display): called with an estimate of the fraction
  // done, in [0, 1), from the thread running the solver. It cannot change any result.
  std::function<void(double)> on_progress;

  // Empty when valid, else what is wrong (one line).
  std::string check() const;
};

enum class LanczosStatus {
  converged,             // every returned pair meets the tolerance
  not_converged,         // the cap was reached; the best pairs are returned with their residuals
  invalid_input,         // k out of range, sizes mismatch, non-positive mass, bad options
  factorization_failed,  // L + sM was not positive definite (L not PSD, or NaN/inf entries)
};

const char* to_string(LanczosStatus status);

struct LanczosResult {
  LanczosStatus status = LanczosStatus::invalid_input;
  std::string message;            // why, when not converged
  Eigen::VectorXd eigenvalues;    // k, ascending
  Eigen::MatrixXd eigenvectors;   // #V by k
  Eigen::VectorXd residuals;      // k, relative (see above)
  int converged = 0;              // returned pairs meeting the tolerance
  int iterations = 0;             // block Lanczos steps
  int restarts = 0;
  long operator_applications = 0;  // vectors through (L + sM)⁻¹
  int corrections = 0;            // blocks whose re-orthogonalisation coefficients were applied
  int second_passes = 0;          // blocks that needed a second full Gram–Schmidt pass
  double shift = 0.0;             // s
  double matrix_norm = 0.0;       // ‖L‖∞
  bool dense = false;             // solved by the dense fallback
  int threads = 1;                // threads used
  long factor_nonzeros = 0;       // of the LDLᵀ factor (0 when dense)
  double factor_seconds = 0.0;    // ordering + factorisation (timing only, never fed back)
  double iteration_seconds = 0.0;  // everything after the factorisation
};

// `L` #V by #V symmetric PSD (both triangles stored); `mass` the #V diagonal of M, or empty for
// M = I; 1 ≤ k < #V. `positions` (#V by 3) lets the nested-dissection ordering compete with
// minimum degree (sparse/fill_reducing_ordering.h; faster on sphere-like meshes); without it the
// factorisation uses minimum degree. Never throws on a numerical outcome.
LanczosResult lanczos_eigensolver(const Eigen::SparseMatrix<double>& L, const Eigen::VectorXd& mass, int k,
                                  const LanczosOptions& options = {}, const Vertices* positions = nullptr);

}  // namespace offsetopt
