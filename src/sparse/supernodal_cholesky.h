// src/sparse (this is the folder's main header): sparse symmetric positive definite solvers for
// the mesh matrices of the layers above. It owns the fill-reducing orderings (nested dissection on
// vertex positions, minimum degree, the symbolic counts that choose between them) and the
// supernodal Cholesky factorisation with its solves. It may include util, optim, mesh, geometry,
// meshio, io and itself; the eigensolver (src/spectral) and the contraction (src/skeleton) use it.
//
// Sparse Cholesky factorisation A = L L^T of a symmetric positive definite matrix by the
// multifrontal method with relaxed supernodes (Duff & Reid 1983; Liu 1992, "The multifrontal
// method for sparse matrix solution"; amalgamation thresholds after CHOLMOD, Chen, Davis, Hager &
// Rajamanickam 2008). Built for the contraction's normal equations, which are refactorised on a
// fixed pattern every step: analyse() once, then factorize() and solve() per step.
//
// Why not Eigen::SimplicialLDLT: its up-looking column-by-column factorisation runs at about
// 1 Gflop/s; the dense frontal kernels here (Eigen's LLT, triangular solve and rank update on
// blocks) reach several times that on the same fill, which is what the skeleton stage spends
// its time on.
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
  bool factor_supernode(int s, const Eigen::SparseMatrix<double>& A, Workspace& work, std::vector<std::vector<double>>& updates,
                        bool split_across_threads);
  // Dense column-major block of supernode s: (k + r) by k, at value_start_[s].
  std::vector<std::size_t> value_start_;
  std::vector<double> values_;
  double stored_nonzeros_ = 0.0;
  int thread_count_ = kDefaultThreads;
  bool factorized_ = false;
};

}  // namespace offsetopt
