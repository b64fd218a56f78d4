#include "spectral/lanczos_eigensolver.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <thread>
#include <vector>

#include "spectral/approximate_eigenpairs.h"
#include "spectral/panel_matrix.h"
#include "spectral/shift_invert_operator.h"
#include "util/parallel.h"
#include "util/rng.h"
#include "util/seconds_since.h"

namespace offsetopt {

std::string LanczosOptions::check() const {
  if (!(tolerance > 0.0) || !(tolerance < 1.0)) return "tolerance must be in (0, 1)";
  if (block_size < 1 || block_size > 64) return "block_size must be in [1, 64]";
  if (max_basis < 0) return "max_basis must be >= 0 (0: automatic)";
  if (max_operator_applications < 0) return "max_operator_applications must be >= 0 (0: automatic)";
  if (!(shift_scale > 0.0) || !std::isfinite(shift_scale)) return "shift_scale must be positive";
  if (!(cluster_tolerance >= 0.0) || !(cluster_tolerance < 1.0)) return "cluster_tolerance must be in [0, 1)";
  if (dense_below < 0) return "dense_below must be >= 0";
  if (threads < 0 || threads > 64) return "threads must be in [0, 64] (0: automatic)";
  return {};
}

const char* to_string(LanczosStatus status) {
  switch (status) {
    case LanczosStatus::converged: return "converged";
    case LanczosStatus::not_converged: return "not_converged";
    case LanczosStatus::invalid_input: return "invalid_input";
    case LanczosStatus::factorization_failed: return "factorization_failed";
  }
  return "unknown";
}

namespace {

using Clock = std::chrono::steady_clock;

// Re-orthogonalisation coefficients below this (relative to the vector) are not subtracted.
constexpr double kCorrectionThreshold = 1e-12;
// The exact residual estimate is computed once every wanted ‖Op y - θ y‖ / θ is below this.
constexpr double kEstimateGate = 1e-2;
// Ritz values closer than this (relative to the largest) are screened as one group.
constexpr double kGroupGap = 1e-6;

// ‖L‖∞ = largest absolute row sum (= column sum, L symmetric); bounds ‖L‖₂ from above.
double infinity_norm(const Eigen::SparseMatrix<double>& L) {
  double largest = 0.0;
  for (Eigen::Index col = 0; col < L.outerSize(); ++col) {
    double sum = 0.0;
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, col); it; ++it) sum += std::abs(it.value());
    largest = std::max(largest, sum);
  }
  return largest;
}

// Turns approximate eigenvectors (columns of X, any scale) into the reported pairs: Rayleigh
// quotients, normalisation, sign, sorting, true residuals. Returns the number meeting `tolerance`.
int finalize_pairs(const Eigen::SparseMatrix<double>& L, const Eigen::VectorXd& mass, double norm_L, double tolerance,
                   Eigen::MatrixXd& X, Eigen::VectorXd& eigenvalues, Eigen::VectorXd& residuals, WorkerPool& pool) {
  const Eigen::Index n = X.rows();
  const int k = static_cast<int>(X.cols());
  const bool generalised = mass.size() > 0;
  // Row-major from here: every pass below reads each row once (L is read once for all k).
  RowMatrix Y = X;
  std::vector<double> norm2(k, 0.0), largest(k, 0.0), factor(k);
  std::vector<Eigen::Index> where(k, 0);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double m = generalised ? mass(i) : 1.0;
    for (int c = 0; c < k; ++c) {
      const double x = Y(i, c);
      norm2[c] += m * x * x;
      if (std::abs(x) > largest[c]) {
        largest[c] = std::abs(x);
        where[c] = i;
      }
    }
  }
  // Normalise (Euclidean or M) with the entry of largest magnitude (first such) positive.
  for (int c = 0; c < k; ++c) {
    factor[c] = norm2[c] > 0.0 ? 1.0 / std::sqrt(norm2[c]) : 0.0;
    if (Y(where[c], c) < 0.0) factor[c] = -factor[c];
  }
  for (Eigen::Index i = 0; i < n; ++i)
    for (int c = 0; c < k; ++c) Y(i, c) *= factor[c];
  // L Y by rows (L symmetric: column i lists row i), then the Rayleigh quotients and residuals.
  RowMatrix LY(n, k);
  pool.run([&](int part) {
    std::vector<double> acc(k);
    for (Eigen::Index i = split_point(n, pool.size(), part); i < split_point(n, pool.size(), part + 1); ++i) {
      std::fill(acc.begin(), acc.end(), 0.0);
      for (Eigen::SparseMatrix<double>::InnerIterator it(L, i); it; ++it) {
        const double* y = Y.data() + it.row() * k;
        const double v = it.value();
        for (int c = 0; c < k; ++c) acc[c] += v * y[c];
      }
      for (int c = 0; c < k; ++c) LY(i, c) = acc[c];
    }
  });
  std::vector<double> yLy(k, 0.0), yMy(k, 0.0);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double m = generalised ? mass(i) : 1.0;
    for (int c = 0; c < k; ++c) {
      yLy[c] += Y(i, c) * LY(i, c);
      yMy[c] += m * Y(i, c) * Y(i, c);
    }
  }
  Eigen::VectorXd lambda(k), residual(k);
  for (int c = 0; c < k; ++c) lambda(c) = yMy[c] > 0.0 ? yLy[c] / yMy[c] : 0.0;
  std::vector<double> r2(k, 0.0), y2(k, 0.0);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double m = generalised ? mass(i) : 1.0;
    for (int c = 0; c < k; ++c) {
      const double r = LY(i, c) - lambda(c) * m * Y(i, c);
      r2[c] += r * r;
      y2[c] += Y(i, c) * Y(i, c);
    }
  }
  for (int c = 0; c < k; ++c)
    residual(c) = y2[c] > 0.0 && norm_L > 0.0 ? std::sqrt(r2[c]) / (norm_L * std::sqrt(y2[c])) : 1.0;
  // Sort by eigenvalue (the Ritz order can differ from the Rayleigh-quotient order by rounding
  // inside a cluster); ties keep the Ritz order.
  std::vector<int> order(static_cast<std::size_t>(k));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return lambda(a) < lambda(b); });
  eigenvalues.resize(k);
  residuals.resize(k);
  int converged = 0;
  for (int c = 0; c < k; ++c) {
    const int from = order[static_cast<std::size_t>(c)];
    X.col(c) = Y.col(from);
    eigenvalues(c) = lambda(from);
    residuals(c) = residual(from);
    if (residuals(c) <= tolerance) ++converged;
  }
  return converged;
}

// Dense fallback: eigenvectors of M^(-1/2) L M^(-1/2) (or L), mapped back by M^(-1/2).
void solve_dense(const Eigen::SparseMatrix<double>& L, const Eigen::VectorXd& mass, int k, Eigen::MatrixXd& X) {
  const Eigen::Index n = L.rows();
  Eigen::MatrixXd A = Eigen::MatrixXd(L);
  if (mass.size()) {
    const Eigen::VectorXd inv_sqrt = mass.cwiseSqrt().cwiseInverse();
    A = inv_sqrt.asDiagonal() * A * inv_sqrt.asDiagonal();
  }
  A = 0.5 * (A + A.transpose()).eval();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(A);
  X = eigen.eigenvectors().leftCols(k);
  if (mass.size())
    for (Eigen::Index i = 0; i < n; ++i) X.row(i) /= std::sqrt(mass(i));
}

// The block Krylov–Schur iteration on Op = D (L + sM)⁻¹ D. See the header for the method.
//
// Invariant: Op Q = Q H + R C, with Q (n by j) and R (n by b) orthonormal and mutually
// orthogonal, H (j by j) symmetric, C (b by j). A step appends R to Q and applies Op to it; the
// Lanczos recurrence says the new block's coefficients on the old basis are Cᵀ, so those are
// removed first (cheap: C is nonzero only on the previous block, or on the kept vectors after a
// restart), then the new block's own coefficients (A = Rᵀ W), and then the coefficients against
// the whole basis are computed (one classical Gram–Schmidt pass, the re-orthogonalisation) and
// subtracted whenever one exceeds rounding level; a second pass runs when the first removed more
// than the DGKS factor 1/√2 (Daniel, Gragg, Kaufman & Stewart 1976). The basis thus stays
// orthonormal to working precision for about one product with the basis per step.
//
// Data: the basis and the blocks are PanelMatrix (spectral/panel_matrix.h); the block handed to
// the operator is also kept row-major (the layout of its triangular solves).
class BlockKrylovSchur {
 public:
  // Derived from LanczosOptions by lanczos_eigensolver, which checks them before the iteration.
  struct Options {
    int k = 0, block = 0, basis = 0;
    long max_applications = 0;
    double tolerance = 0.0, cluster_tolerance = 0.0, shift = 0.0, norm_L = 0.0;
    std::uint64_t seed = 0;
    std::function<void(double)> on_progress;  // fraction of the basis built (no restart), < 1

    // Empty when the iteration can run on these, else what is wrong (one line).
    std::string check() const {
      if (k < 1 || block < 1) return "k and block must be >= 1";
      if (basis < k + 1 + 2 * block || basis % block != 0)
        return "basis must be a multiple of block >= k + 1 + 2 block";
      if (max_applications < 1) return "max_applications must be >= 1";
      if (!(tolerance > 0.0) || !(cluster_tolerance >= 0.0)) return "tolerance must be > 0, cluster_tolerance >= 0";
      if (!(shift > 0.0) || !std::isfinite(shift) || !std::isfinite(norm_L))
        return "shift and norm_L must be finite, shift > 0";
      return {};
    }
  };

  BlockKrylovSchur(const ShiftInvertOperator& op, const Eigen::SparseMatrix<double>& L, const Eigen::VectorXd& mass,
                   const Options& settings, WorkerPool& pool)
      : op_(op), L_(L), pool_(&pool), n_(op.size()), k_(settings.k), b_(settings.block), m_(settings.basis),
        settings_(settings), rng_(settings.seed) {
    scale_.resize(n_);
    double largest_mass = 1.0;
    for (Eigen::Index i = 0; i < n_; ++i) {
      scale_(i) = mass.size() ? std::sqrt(mass(i)) : 1.0;
      if (mass.size()) largest_mass = i == 0 ? mass(i) : std::max(largest_mass, mass(i));
    }
    // ‖φ‖₂ = ‖D⁻¹ y‖₂ ≥ 1 / sqrt(max M) for a unit y: the estimate below uses this bound, so
    // it can only overstate the residual.
    smallest_phi_norm_ = 1.0 / std::sqrt(largest_mass);
  }

  // Runs until the convergence test passes or the cap is hit. Returns true when converged.
  bool run();
  // φ = D⁻¹ Q z for the k wanted Ritz pairs (n by k), from the last Rayleigh–Ritz.
  Eigen::MatrixXd wanted_vectors() const;
  // After a failed verification: demand `factor` times smaller estimates and continue.
  void tighten(double factor) { internal_scale_ *= factor; }

  int iterations() const { return iterations_; }
  int restarts() const { return restarts_; }
  long applications() const { return applications_; }
  int second_passes() const { return second_passes_; }
  int corrections() const { return corrections_; }

 private:
  void start();
  void expand();
  void rayleigh_ritz();
  int required_pairs(const Eigen::VectorXd& theta) const;
  bool converged_estimate();
  bool proven_unconverged();
  bool restart_due() const;
  void restart();
  void ensure_capacity(int columns);
  void update_residual_gram();
  // Orthonormalises the columns of W (n by b, already orthogonal to Q(:, 0:j)); S (b by b)
  // gets W_in = W_out S. Dependent columns are replaced by random directions (orthogonal to
  // everything) with a zero coefficient.
  void orthonormalize(PanelMatrix& W, int j, const Eigen::VectorXd& reference_norms, Eigen::MatrixXd& S);
  bool cholesky_qr(PanelMatrix& W, const Eigen::VectorXd& reference_norms, Eigen::MatrixXd& S) const;
  void gram_schmidt_with_replacement(PanelMatrix& W, int j, const Eigen::VectorXd& reference_norms,
                                     Eigen::MatrixXd& S);
  // One classical Gram–Schmidt pass of the columns of W against Q(:, first:last); returns the
  // coefficients (last - first by W.cols(), row-major).
  RowMatrix project_out(PanelMatrix& W, int first, int last) const;

  const ShiftInvertOperator& op_;
  const Eigen::SparseMatrix<double>& L_;
  WorkerPool* pool_;
  Eigen::Index n_;
  int k_, b_, m_, capacity_ = 0;
  Options settings_;
  Rng rng_;
  Eigen::VectorXd scale_;  // D
  double smallest_phi_norm_ = 1.0;
  double internal_scale_ = 1.0;

  PanelMatrix Q_;         // basis, columns 0:j_ active
  PanelMatrix R_;         // next block
  RowMatrix R_rows_;      // the same, row-major, for the operator and the residual estimate
  PanelMatrix previous_;  // the block before R (empty after a restart)
  Eigen::MatrixXd H_;     // projected operator, j_ by j_ active
  Eigen::MatrixXd C_;     // coupling, b by j_ active; zero left of coupled_from_
  int coupled_from_ = 0;
  int j_ = 0;
  Eigen::MatrixXd residual_gram_;  // (K D⁻¹ R)ᵀ (K D⁻¹ R), b by b
  bool gram_current_ = false;      // residual_gram_ belongs to the current R

  // Last Rayleigh–Ritz: θ descending, Z (j by j), C Z and ‖C z‖.
  Eigen::VectorXd theta_;
  Eigen::MatrixXd Z_;
  Eigen::MatrixXd coupling_;
  Eigen::VectorXd rho_;
  int required_ = 0;  // pairs that must converge (k extended to the end of its cluster)
  bool ritz_current_ = false;  // theta_, Z_, coupling_, rho_ belong to the current H
  bool screening_ = true;      // proven_unconverged is still worth trying

  int iterations_ = 0, restarts_ = 0, second_passes_ = 0, corrections_ = 0;
  long applications_ = 0;
  double largest_theta_ = 0.0;
};

RowMatrix BlockKrylovSchur::project_out(PanelMatrix& W, int first, int last) const {
  const int b = W.cols();
  RowMatrix coefficients(last - first, b);
  if (last <= first) return coefficients;
  panel_project(Q_, first, last - first, W, 0, b, coefficients.data(), pool_);
  panel_subtract(Q_, first, last - first, coefficients.data(), W, 0, b, pool_);
  return coefficients;
}

// W ← W U⁻¹ for an upper triangular U (b by b): a product with the explicit inverse, so the rows
// are independent (a row-by-row triangular solve is a chain of dependent divisions).
void apply_inverse_upper(PanelMatrix& W, const Eigen::MatrixXd& U, WorkerPool* pool) {
  const int b = W.cols();
  const RowMatrix inverse = U.triangularView<Eigen::Upper>().solve(Eigen::MatrixXd::Identity(b, b));
  panel_combine(W, 0, b, inverse.data(), b, W, 0, pool);
}

// CholQR twice (Yamamoto et al. 2015): orthonormal to working precision when cond(W) < ~1e7.
// Returns false when W is too ill-conditioned or rank deficient; S then holds what has been
// applied (W = W_in S⁻¹ spans the same space).
bool BlockKrylovSchur::cholesky_qr(PanelMatrix& W, const Eigen::VectorXd& reference_norms, Eigen::MatrixXd& S) const {
  const int b = W.cols();
  RowMatrix gram(b, b);
  panel_project(W, 0, b, W, 0, b, gram.data(), pool_);
  Eigen::MatrixXd U[2];
  S = Eigen::MatrixXd::Identity(b, b);
  for (int pass = 0; pass < 2; ++pass) {
    Eigen::LLT<Eigen::MatrixXd> llt(Eigen::MatrixXd(gram).selfadjointView<Eigen::Lower>());
    if (llt.info() != Eigen::Success) return false;
    U[pass] = llt.matrixU();
    for (int c = 0; c < b; ++c) {
      if (!(U[pass](c, c) > 0.0)) return false;
      if (pass == 0 && (U[0](c, c) < 1e-7 * U[0].diagonal().maxCoeff() ||
                        U[0](c, c) <= 1e-12 * std::max(reference_norms(c), largest_theta_)))
        return false;
    }
    if (pass == 1) break;
    apply_inverse_upper(W, U[0], pool_);
    S = U[0];
    panel_project(W, 0, b, W, 0, b, gram.data(), pool_);
  }
  apply_inverse_upper(W, U[1], pool_);
  S = U[1] * U[0];
  return true;
}

void BlockKrylovSchur::gram_schmidt_with_replacement(PanelMatrix& W, int j, const Eigen::VectorXd& reference_norms,
                                                     Eigen::MatrixXd& S) {
  const int b = W.cols();
  S = Eigen::MatrixXd::Zero(b, b);
  // Column c of W against columns d < c (two passes), rows in order.
  auto orthogonalise_column = [&](PanelMatrix& M, int c, PanelMatrix* against, int count, Eigen::MatrixXd* record) {
    for (int pass = 0; pass < 2; ++pass) {
      for (int d = 0; d < count; ++d) {
        double h = 0.0;
        for (Eigen::Index p = 0; p < M.panels(); ++p) {
          const double* x = M.column(p, c);
          const double* y = against->column(p, d);
          for (Eigen::Index i = 0; i < kPanelRows; ++i) h += y[i] * x[i];
        }
        if (record) (*record)(d, c) += h;
        for (Eigen::Index p = 0; p < M.panels(); ++p) {
          double* x = M.column(p, c);
          const double* y = against->column(p, d);
          for (Eigen::Index i = 0; i < kPanelRows; ++i) x[i] -= h * y[i];
        }
      }
    }
  };
  for (int c = 0; c < b; ++c) {
    orthogonalise_column(W, c, &W, c, &S);
    double norm = panel_column_norms(W, c, 1)(0);
    // Nothing (numerically) left outside the basis: the Krylov space is invariant in that
    // direction. Continue with a random direction, coupled by 0.
    const double floor = 1e-12 * std::max(reference_norms(c), largest_theta_);
    if (norm > floor && norm > 0.0) {
      S(c, c) = norm;
      for (Eigen::Index p = 0; p < W.panels(); ++p)
        for (Eigen::Index i = 0; i < kPanelRows; ++i) W.column(p, c)[i] /= norm;
      continue;
    }
    for (Eigen::Index p = 0; p < W.panels(); ++p) std::fill(W.column(p, c), W.column(p, c) + kPanelRows, 0.0);
    for (int attempt = 0; attempt < 3; ++attempt) {
      PanelMatrix fresh(n_, 1);
      for (Eigen::Index i = 0; i < n_; ++i) fresh(i, 0) = rng_.uniform(-1.0, 1.0);
      for (int pass = 0; pass < 2; ++pass) {
        project_out(fresh, 0, j);
        orthogonalise_column(fresh, 0, &W, c, nullptr);
      }
      norm = panel_column_norms(fresh, 0, 1)(0);
      if (norm > 1e-6 * std::sqrt(static_cast<double>(n_) / 3.0)) {
        for (Eigen::Index p = 0; p < W.panels(); ++p)
          for (Eigen::Index i = 0; i < kPanelRows; ++i) W.column(p, c)[i] = fresh.column(p, 0)[i] / norm;
        break;
      }
    }
  }
}

void BlockKrylovSchur::orthonormalize(PanelMatrix& W, int j, const Eigen::VectorXd& reference_norms,
                                      Eigen::MatrixXd& S) {
  Eigen::MatrixXd applied;
  if (cholesky_qr(W, reference_norms, applied)) {
    S = applied;
    return;
  }
  // W = W_in applied⁻¹ now; Gram–Schmidt finishes: W_in = W_out S_gs applied.
  Eigen::MatrixXd rest;
  gram_schmidt_with_replacement(W, j, reference_norms, rest);
  S = rest * applied;
}

void BlockKrylovSchur::ensure_capacity(int columns) {
  if (columns <= capacity_) return;
  Q_.resize_columns(columns);
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(columns, columns);
  H.topLeftCorner(capacity_, capacity_) = H_;
  H_ = std::move(H);
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(b_, columns);
  C.leftCols(capacity_) = C_;
  C_ = std::move(C);
  capacity_ = columns;
}

void BlockKrylovSchur::start() {
  capacity_ = std::min(m_, ((k_ + 4 * b_) / b_ + 1) * b_);
  Q_.resize(n_, capacity_);
  H_ = Eigen::MatrixXd::Zero(capacity_, capacity_);
  C_ = Eigen::MatrixXd::Zero(b_, capacity_);
  R_.resize(n_, b_);
  for (Eigen::Index i = 0; i < n_; ++i)
    for (int c = 0; c < b_; ++c) R_(i, c) = rng_.uniform(-1.0, 1.0);
  Eigen::MatrixXd S;
  orthonormalize(R_, 0, panel_column_norms(R_, 0, b_), S);
  R_rows_.resize(n_, b_);
  R_.get_columns(0, b_, R_rows_.data(), b_);
  j_ = 0;
  coupled_from_ = 0;
}

// residual_gram_ = Tᵀ T with T = K D⁻¹ R, K = L + sM: for a Ritz pair (θ, y = Q z) the
// residual of φ = D⁻¹ y in the original problem is L φ - λ M φ = -K D⁻¹ R (C z) / θ.
void BlockKrylovSchur::update_residual_gram() {
  const int b = b_;
  PanelMatrix T(n_, b);
  // L is symmetric: column `row` lists the entries of row `row`. Panels split among threads.
  auto rows = [&](Eigen::Index begin, Eigen::Index end) {
    std::vector<double> acc(static_cast<std::size_t>(b));
    for (Eigen::Index row = begin; row < end; ++row) {
      std::fill(acc.begin(), acc.end(), 0.0);
      for (Eigen::SparseMatrix<double>::InnerIterator it(L_, row); it; ++it) {
        const double* r = R_rows_.data() + it.row() * b;
        const double v = it.value() / scale_(it.row());
        for (int c = 0; c < b; ++c) acc[c] += v * r[c];
      }
      const double diagonal = settings_.shift * scale_(row);  // s M_ii / D_ii
      for (int c = 0; c < b; ++c) T(row, c) = acc[c] + diagonal * R_rows_(row, c);
    }
  };
  const Eigen::Index panels = T.panels();
  pool_->run([&](int part) {
    const Eigen::Index p0 = split_point(panels, pool_->size(), part), p1 = split_point(panels, pool_->size(), part + 1);
    rows(std::min(n_, p0 * kPanelRows), std::min(n_, p1 * kPanelRows));
  });
  RowMatrix gram(b, b);
  panel_project(T, 0, b, T, 0, b, gram.data(), pool_);
  residual_gram_ = gram;
  gram_current_ = true;
}

void BlockKrylovSchur::expand() {
  const int j = j_, b = b_;
  Q_.copy_columns(j, R_, 0, b);
  H_.block(j, 0, b, j) = C_.leftCols(j);
  H_.block(0, j, j, b) = C_.leftCols(j).transpose();

  RowMatrix applied;
  op_.apply(R_rows_.data(), b, b, applied, pool_);
  applications_ += b;
  ++iterations_;
  PanelMatrix W(n_, b);
  W.set_columns(0, b, applied.data(), b);

  // The recurrence: coefficients Cᵀ on the old basis (the previous block, or after a restart the
  // kept vectors), then A = Rᵀ W on the new block.
  if (j > coupled_from_) {
    const RowMatrix known = C_.block(0, coupled_from_, b, j - coupled_from_).transpose();
    if (coupled_from_ == j - b && previous_.cols() == b)
      panel_subtract(previous_, 0, b, known.data(), W, 0, b, pool_);
    else
      panel_subtract(Q_, coupled_from_, j - coupled_from_, known.data(), W, 0, b, pool_);
  }
  RowMatrix diagonal(b, b);
  panel_project(R_, 0, b, W, 0, b, diagonal.data(), pool_);
  panel_subtract(R_, 0, b, diagonal.data(), W, 0, b, pool_);
  Eigen::MatrixXd diagonal_block = diagonal;

  // Re-orthogonalisation against the whole basis (see the class comment); the norm after a
  // pass is |before|² - |coefficients|² (Q orthonormal).
  const Eigen::VectorXd before = panel_column_norms(W, 0, b);
  RowMatrix correction(j + b, b);
  panel_project(Q_, 0, j + b, W, 0, b, correction.data(), pool_);
  bool significant = false, again = false;
  for (int c = 0; c < b; ++c) {
    const double largest = correction.col(c).cwiseAbs().maxCoeff();
    significant = significant || largest > kCorrectionThreshold * before(c);
    again = again || before(c) * before(c) - correction.col(c).squaredNorm() < 0.5 * before(c) * before(c);
  }
  if (significant) {
    ++corrections_;
    panel_subtract(Q_, 0, j + b, correction.data(), W, 0, b, pool_);
    diagonal_block += correction.bottomRows(b);
    if (again) {
      ++second_passes_;
      correction = project_out(W, 0, j + b);
      diagonal_block += correction.bottomRows(b);
    }
  }
  H_.block(j, j, b, b) = 0.5 * (diagonal_block + diagonal_block.transpose());

  Eigen::MatrixXd S;
  orthonormalize(W, j + b, before, S);
  previous_ = std::move(R_);
  R_ = std::move(W);
  R_.get_columns(0, b, R_rows_.data(), b);
  C_.setZero();
  C_.block(0, j, b, b) = S;
  coupled_from_ = j;
  j_ = j + b;
  gram_current_ = false;
  ritz_current_ = false;
}

void BlockKrylovSchur::rayleigh_ritz() {
  const int j = j_;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(H_.topLeftCorner(j, j));
  theta_.resize(j);
  Z_.resize(j, j);
  for (int i = 0; i < j; ++i) {  // descending θ = ascending λ
    theta_(i) = eigen.eigenvalues()(j - 1 - i);
    Z_.col(i) = eigen.eigenvectors().col(j - 1 - i);
  }
  largest_theta_ = std::max(largest_theta_, theta_(0));
  coupling_ = C_.leftCols(j) * Z_;
  rho_.resize(j);
  for (int i = 0; i < j; ++i) rho_(i) = coupling_.col(i).norm();
  ritz_current_ = true;
}

// k extended to the end of its cluster (θ descending).
int BlockKrylovSchur::required_pairs(const Eigen::VectorXd& theta) const {
  const int j = static_cast<int>(theta.size());
  const double shift = settings_.shift;
  auto lambda = [&](int i) { return 1.0 / theta(i) - shift; };
  int required = std::min(k_, j);
  while (required < j && std::abs(lambda(required) - lambda(required - 1)) <=
                             settings_.cluster_tolerance * (std::abs(lambda(required - 1)) + shift))
    ++required;
  return required;
}

// Whether the next pass of run() restarts (the basis cannot grow past the step after this one).
bool BlockKrylovSchur::restart_due() const {
  int limit = m_;
  if (required_ + 1 + 2 * b_ > limit) limit = ((required_ + 1 + 2 * b_ + b_ - 1) / b_) * b_;
  return j_ + b_ > limit;
}

// True when this step provably fails converged_estimate, shown from the Ritz values (bit for bit
// those of rayleigh_ritz) and approximate Ritz vectors with bounded error
// (spectral/approximate_eigenpairs.h): then the full decomposition (about four times the work
// at these sizes) is skipped, with the same state for everything that follows (required_,
// largest_theta_, the residual Gram matrix, which depends on R alone). Returns false, leaving
// the decision to the full path, when a restart is due (it needs Z) or nothing can be proven.
// Pairs are tried from the last wanted back: the slowest to converge fail first.
bool BlockKrylovSchur::proven_unconverged() {
  const int j = j_;
  const ApproximateEigenpairs ritz(H_.topLeftCorner(j, j));
  if (!ritz.ok()) return false;
  const Eigen::VectorXd& theta = ritz.values();
  largest_theta_ = std::max(largest_theta_, theta(0));
  required_ = required_pairs(theta);
  if (restart_due()) return false;
  if (required_ >= j) return true;
  const double eps = std::numeric_limits<double>::epsilon();
  const auto C = C_.leftCols(j);
  const double C_norm = C.norm();
  const double rounding = 8.0 * static_cast<double>(j) * eps;
  const double tol = settings_.tolerance * internal_scale_;
  const double denominator = settings_.norm_L * smallest_phi_norm_;
  // Groups of (nearly) equal values, the last wanted first. A group's test reads sums over its
  // members, which do not depend on the basis chosen inside its subspace: when the sum of
  // squares exceeds the sum of the squared limits, some member exceeds its own.
  const double group_gap = kGroupGap * std::abs(theta(0));
  Eigen::MatrixXd V;
  for (int end = required_; end > 0;) {
    int begin = end - 1;
    while (begin > 0 && theta(begin - 1) - theta(begin) <= group_gap) --begin;
    const bool straddles = end == required_ && theta(required_ - 1) - theta(required_) <= group_gap;
    const int count = end - begin;
    const int first = begin;
    end = begin;
    if (straddles) continue;
    const double distance = ritz.subspace(first, count, V);
    if (!std::isfinite(distance)) continue;
    const Eigen::MatrixXd coupling = C * V;
    const double root_count = std::sqrt(static_cast<double>(count));
    const double rho = coupling.norm(), rho_error = C_norm * root_count * (distance + rounding);
    const double gate_limit = kEstimateGate * theta.segment(first, count).norm();
    if (rho - rho_error > gate_limit * (1.0 + 1e-9)) return true;
    // The gate may pass or not: a failed estimate means not converged either way.
    if (!gram_current_) update_residual_gram();
    const double squared = (coupling.transpose() * residual_gram_ * coupling).trace();
    const double estimate = std::sqrt(std::max(squared, 0.0));
    const double error = std::sqrt(residual_gram_.norm()) * (rho_error + std::sqrt(rounding) * rho);
    if (estimate - error > tol * denominator * theta.segment(first, count).cwiseAbs().norm() * (1.0 + 1e-6))
      return true;
  }
  return false;
}

bool BlockKrylovSchur::converged_estimate() {
  const int j = j_;
  const int required = required_pairs(theta_);
  required_ = required;
  if (required >= j) return false;  // the pair past the cluster is not in the basis yet
  // Cheap gate first: the residual in the shifted-inverted problem, relative to θ, is far above
  // the true relative residual only on meshes with very uneven vertex areas; until it is below
  // kEstimateGate the exact estimate is not worth a pass over L.
  for (int i = 0; i < required; ++i)
    if (!(rho_(i) <= kEstimateGate * theta_(i))) return false;
  if (!gram_current_) update_residual_gram();
  const double tol = settings_.tolerance * internal_scale_;
  const double denominator = settings_.norm_L * smallest_phi_norm_;
  for (int i = 0; i < required; ++i) {
    const double squared = coupling_.col(i).dot(residual_gram_ * coupling_.col(i));
    const double estimate = std::sqrt(std::max(squared, 0.0)) / (std::abs(theta_(i)) * denominator);
    if (!(estimate <= tol)) return false;
  }
  // The first pair past the cluster only needs its value accurate enough to show the gap.
  const double guard = std::max(tol, 0.1 * settings_.cluster_tolerance);
  return rho_(required) <= guard * theta_(required);
}

void BlockKrylovSchur::restart() {
  const int j = j_;
  // Keep the wanted pairs, the one past the cluster, and half of the rest (the thick part).
  const int wanted = std::min(required_ + 1, j - b_);
  int keep = wanted + (m_ - wanted) / 2;
  keep = std::min(keep, m_ - b_);
  keep = std::max(keep, std::min(wanted, m_ - b_));
  const RowMatrix Zkeep = Z_.leftCols(keep);
  panel_combine(Q_, 0, j, Zkeep.data(), keep, Q_, 0, pool_);
  H_.setZero();
  for (int i = 0; i < keep; ++i) H_(i, i) = theta_(i);
  Eigen::MatrixXd coupling = C_.leftCols(j) * Z_.leftCols(keep);
  // Lock: a pair whose residual is far below the tolerance is decoupled from the rest.
  const double lock = 0.01 * settings_.tolerance * internal_scale_;
  for (int i = 0; i < keep; ++i)
    if (rho_(i) <= lock * theta_(i)) coupling.col(i).setZero();
  C_.setZero();
  C_.leftCols(keep) = coupling;
  coupled_from_ = 0;
  previous_ = PanelMatrix();
  j_ = keep;
  ++restarts_;
  ritz_current_ = false;
}

bool BlockKrylovSchur::run() {
  if (Q_.cols() == 0) start();
  while (true) {
    if (j_ + b_ > capacity_) {
      // A cluster reaching past the basis: grow the basis instead of restarting in vain.
      if (required_ + 1 + 2 * b_ > m_) m_ = ((required_ + 1 + 2 * b_ + b_ - 1) / b_) * b_;
      if (capacity_ < m_) {
        ensure_capacity(std::min(m_, ((capacity_ * 3 / 2 + b_ - 1) / b_) * b_));
        continue;
      }
      restart();
    }
    if (applications_ + b_ > settings_.max_applications) {
      if (!ritz_current_) rayleigh_ritz();  // the returned vectors come from the current basis
      return false;
    }
    expand();
    if (settings_.on_progress)
      settings_.on_progress(std::min(0.99, static_cast<double>(applications_) / static_cast<double>(settings_.basis)));
    if (j_ > k_) {
      // Once a screen fails to prove anything, the iteration is near its end (the estimates are
      // at the level of the vectors' rounding): the remaining steps go straight to the full path.
      if (screening_ && proven_unconverged()) continue;
      screening_ = false;
      rayleigh_ritz();
      if (converged_estimate()) return true;
    }
  }
}

Eigen::MatrixXd BlockKrylovSchur::wanted_vectors() const {
  const int j = j_;
  const int count = std::min(k_, j);
  const RowMatrix Zk = Z_.leftCols(count);
  PanelMatrix Y(n_, count);
  panel_combine(Q_, 0, j, Zk.data(), count, Y, 0, pool_);
  // φ = D⁻¹ y, column-major.
  Eigen::MatrixXd X(n_, count);
  for (int c = 0; c < count; ++c)
    for (Eigen::Index p = 0; p < Y.panels(); ++p) {
      const double* y = Y.column(p, c);
      const Eigen::Index rows = std::min(kPanelRows, n_ - p * kPanelRows);
      for (Eigen::Index i = 0; i < rows; ++i) X(p * kPanelRows + i, c) = y[i] / scale_(p * kPanelRows + i);
    }
  return X;
}

}  // namespace

LanczosResult lanczos_eigensolver(const Eigen::SparseMatrix<double>& L, const Eigen::VectorXd& mass, int k,
                                  const LanczosOptions& options, const Vertices* positions) {
  LanczosResult result;
  const auto fail = [&](LanczosStatus status, std::string message) {
    result.status = status;
    result.message = std::move(message);
    return result;
  };
  if (std::string problem = options.check(); !problem.empty()) return fail(LanczosStatus::invalid_input, problem);
  const Eigen::Index n = L.rows();
  if (L.cols() != n) return fail(LanczosStatus::invalid_input, "the matrix is not square");
  if (mass.size() != 0 && mass.size() != n) return fail(LanczosStatus::invalid_input, "mass has the wrong size");
  if (positions && positions->rows() != n) return fail(LanczosStatus::invalid_input, "positions have the wrong size");
  if (k < 1) return fail(LanczosStatus::invalid_input, "k must be at least 1");
  if (k >= n)
    return fail(LanczosStatus::invalid_input, "k = " + std::to_string(k) + " must be below the number of rows (" +
                                                 std::to_string(n) + ")");
  for (Eigen::Index i = 0; i < mass.size(); ++i)
    if (!(mass(i) > 0.0) || !std::isfinite(mass(i)))
      return fail(LanczosStatus::invalid_input, "mass must be positive and finite (row " + std::to_string(i) + ")");

  result.matrix_norm = infinity_norm(L);
  double trace_L = 0.0, trace_M = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    trace_L += L.coeff(i, i);
    trace_M += mass.size() ? mass(i) : 1.0;
  }
  result.shift = options.shift_scale * trace_L / (static_cast<double>(n) * trace_M);
  if (!(result.shift > 0.0) || !std::isfinite(result.shift) || !std::isfinite(result.matrix_norm))
    return fail(LanczosStatus::invalid_input, "the matrix has no positive finite diagonal (empty or degenerate mesh?)");

  const int b = std::min<int>(options.block_size, static_cast<int>(n));
  int basis = options.max_basis;
  if (basis == 0) basis = std::max(3 * k, k + 24 * b);
  basis = std::max(basis, k + 1 + 2 * b);
  basis = ((basis + b - 1) / b) * b;
  const long cap = options.max_operator_applications > 0 ? options.max_operator_applications : 200L * (k + b);

  const unsigned hardware = std::thread::hardware_concurrency();
  const int threads = options.threads > 0 ? options.threads : static_cast<int>(std::max(1u, std::min(2u, hardware)));
  WorkerPool pool(threads);
  result.threads = threads;

  const Clock::time_point start = Clock::now();
  Eigen::MatrixXd X;
  if (n <= options.dense_below || 3L * basis > n) {
    result.dense = true;
    solve_dense(L, mass, k, X);
    result.iteration_seconds = seconds_since(start);
    result.eigenvectors = std::move(X);
    result.converged = finalize_pairs(L, mass, result.matrix_norm, options.tolerance, result.eigenvectors,
                                      result.eigenvalues, result.residuals, pool);
    result.status = result.converged == k ? LanczosStatus::converged : LanczosStatus::not_converged;
    if (result.status != LanczosStatus::converged) result.message = "the dense solver missed the tolerance";
    return result;
  }

  ShiftInvertOperator op(L, mass, result.shift, positions, &pool);
  result.factor_seconds = seconds_since(start);
  result.factor_nonzeros = static_cast<long>(op.factor_nonzeros());
  if (op.status() != ShiftInvertOperator::Status::ok)
    return fail(LanczosStatus::factorization_failed, "L + sM is not positive definite (is L positive semi-definite?)");

  const Clock::time_point iterate = Clock::now();
  BlockKrylovSchur::Options settings;
  settings.k = k;
  settings.block = b;
  settings.basis = basis;
  settings.max_applications = cap;
  settings.tolerance = options.tolerance;
  settings.cluster_tolerance = options.cluster_tolerance;
  settings.shift = result.shift;
  settings.norm_L = result.matrix_norm;
  settings.seed = options.seed;
  settings.on_progress = options.on_progress;
  if (const std::string problem = settings.check(); !problem.empty())
    return fail(LanczosStatus::invalid_input, "iteration options: " + problem);
  BlockKrylovSchur solver(op, L, mass, settings, pool);
  bool converged = false;
  for (int verification = 0; verification < 6; ++verification) {
    converged = solver.run();
    result.eigenvectors = solver.wanted_vectors();
    result.converged = finalize_pairs(L, mass, result.matrix_norm, options.tolerance, result.eigenvectors,
                                      result.eigenvalues, result.residuals, pool);
    if (!converged || result.converged == k) break;
    // The estimate said yes but a true residual says no: ask for `worst/tolerance` more.
    const double worst = result.residuals.maxCoeff();
    solver.tighten(std::max(0.01, std::min(0.5, options.tolerance / worst)));
  }
  result.iterations = solver.iterations();
  result.restarts = solver.restarts();
  result.operator_applications = solver.applications();
  result.second_passes = solver.second_passes();
  result.corrections = solver.corrections();
  result.iteration_seconds = seconds_since(iterate);
  if (result.converged == k) {
    result.status = LanczosStatus::converged;
  } else {
    result.status = LanczosStatus::not_converged;
    result.message = converged ? "residuals stayed above the tolerance" : "operator-application cap reached";
  }
  return result;
}

}  // namespace offsetopt
