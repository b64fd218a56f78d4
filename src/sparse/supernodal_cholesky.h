// src/sparse (this is the folder's main header): sparse symmetric positive definite solvers for
// the mesh matrices of the layers above. It owns the fill-reducing orderings (nested dissection on
// vertex positions, minimum degree, the symbolic counts that choose between them) and the
// supernodal Cholesky factorisation with its solves. It may include util, optim, mesh, geometry,
// meshio, io and itself; the eigensolver (src/spectral) and the contraction (src/skeleton) use it.
//
// Sparse Cholesky factorisation A = L L^T of a symmetric positive definite matrix by the
// multifrontal method with relaxed supernodes (Duff & Reid 1983; Liu 1992, "The multifrontal
// method for sparse matrix solution"; amalgamation thresholds after CHOLMOD, Chen, Davis, Hager &
// Rajamanickam 2008). The project's one sparse factorisation: the contraction's normal equations
// (src/skeleton), refactorised on a fixed pattern every step (analyse() once, then factorize()
// and solve() per step), and the eigensolver's L + sM (src/spectral, shift-invert), which takes
// the factor as a unit-lower LDLᵀ in supernodes for its own block solves (block_ldlt()).
//
// Why not Eigen::SimplicialLDLT: its up-looking column-by-column factorisation runs at about
// 1 Gflop/s; the dense frontal kernels here (Eigen's LLT, triangular solve and rank update on
// blocks) reach several times that on the same fill. Measured (CPU seconds, one thread, a loaded
// 2-core machine): the contraction's L^T L + I, numeric factorisation, 0.18 against 1.07 s
// (40,962-vertex icosphere), 1.62 against 16.4 s (163,842), 1.02 against 8.04 s (the 172,974-
// vertex Armadillo); the eigensolver's L + sM, ordering and factorisation together, 1.14 against
// 2.07 s (163,842-vertex icosphere) and 1.32 against 1.91 s (Armadillo), where SimplicialLDLT was
// split at the first dissection level with a dense separator.
//
// The matrix is used in the order given (the caller applies a fill-reducing ordering); internally
// the columns are renumbered by a postorder of the elimination tree, which changes neither the
// fill nor the result's meaning. Each front is factorised right-looking in panels of at most
// kPanelWidth columns, and the solves cut their products the same way, so every dense kernel's
// inner dimension stays below Eigen's smallest cache block (Eigen splits the inner dimension at
// 120 or more for any L1 cache of 8 KB or more): the summation order, and so every bit of the
// result, is the same on every machine.
#pragma once
#include <Eigen/Core>
#include <Eigen/Sparse>
#include <vector>

namespace offsetopt {

class WorkerPool;  // util/parallel.h

// A factor A = L D Lᵀ with L unit lower, stored for block triangular solves. Columns are in the
// factor's own order: column j is the caller's row/column order[j]. A supernode is a run of
// columns [first, first + width) whose strictly lower triangle is packed by rows at `triangle`
// (row i holds its i entries), and whose rows below the run, rows[row_begin, row_begin +
// row_count) (increasing), form a row-major row_count by width block at `below`.
struct BlockLdlt {
  struct Supernode {
    int first = 0, width = 0;
    int row_begin = 0, row_count = 0;
    std::size_t triangle = 0, below = 0;
  };
  std::vector<int> order;
  std::vector<double> pivots;  // D, factor order
  std::vector<Supernode> supernodes;
  std::vector<int> rows;
  std::vector<double> values;
};

class SupernodalCholesky {
 public:
  static constexpr int kPanelWidth = 64;
  // Independent subtrees of the assembly tree are factorised on this many threads by default (a
  // partition fixed by the symbolic structure; every number computed is independent of it).
  static constexpr int kDefaultThreads = 2;
  // Trailing updates of at least this many rows are computed in two fixed parts (one per thread
  // at the top of the tree).
  static constexpr int kSplitUpdate = 256;

  // Symbolic analysis of `pattern` (square, symmetric, both triangles stored, column-major).
  // Entries present in the pattern may be numerically zero; they are kept.
  void analyze(const Eigen::SparseMatrix<double>& pattern);

  // Numeric factorisation of a matrix with exactly the analysed pattern (only its lower triangle
  // is read). Returns false, leaving the factor unusable, when a pivot is not positive.
  bool factorize(const Eigen::SparseMatrix<double>& A);

  // Solves A X = B for the last successful factorisation, in place (B is n by any).
  void solve_in_place(Eigen::MatrixXd& B) const;

  // The last successful factorisation as L D Lᵀ (L = L_chol diag(L_chol)⁻¹, D = diag(L_chol)²),
  // supernodes cut to at most `max_width` columns. Throws std::logic_error without one.
  BlockLdlt block_ldlt(int max_width) const;

  // Threads for factorize() (>= 1); the results are bit-identical for any count.
  void set_thread_count(int threads);

  Eigen::Index rows() const { return n_; }
  // Stored entries of L, explicit zeros of relaxed supernodes included.
  double stored_nonzeros() const { return stored_nonzeros_; }
  int supernode_count() const { return static_cast<int>(first_column_.size()) - 1; }

 private:
  Eigen::Index n_ = 0;
  std::vector<int> to_caller_;    // internal column -> caller's index
  std::vector<int> from_caller_;  // caller's index -> internal column
  // Supernode s owns internal columns [first_column_[s], first_column_[s + 1]); its rows below
  // those columns are row_indices_[row_start_[s], row_start_[s + 1]) (internal, increasing).
  std::vector<int> first_column_;
  std::vector<int> row_start_;
  std::vector<int> row_indices_;
  std::vector<int> parent_supernode_;  // -1 at roots
  std::vector<int> child_start_, child_list_;  // children of each supernode, increasing
  std::vector<std::vector<int>> thread_lists_;  // supernodes per thread, increasing
  std::vector<int> top_list_;                   // the rest, done after the threads, increasing

  struct Workspace {
    std::vector<int> local;
    std::vector<double> front;
  };
  void plan_threads(int threads);
  // `split_pool`: the pool that takes the second part of a large trailing update (nullptr: both
  // parts on the calling thread, in the same order of parts).
  bool factor_supernode(int s, const Eigen::SparseMatrix<double>& A, Workspace& work, std::vector<std::vector<double>>& updates,
                        WorkerPool* split_pool);
  // Dense column-major block of supernode s: (k + r) by k, at value_start_[s].
  std::vector<std::size_t> value_start_;
  std::vector<double> values_;
  double stored_nonzeros_ = 0.0;
  int thread_count_ = kDefaultThreads;
  bool factorized_ = false;
};

}  // namespace offsetopt
