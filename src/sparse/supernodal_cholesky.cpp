#include "sparse/supernodal_cholesky.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <stdexcept>

#include "util/parallel.h"

namespace offsetopt {

namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

// Relaxed amalgamation (CHOLMOD's defaults): merging a supernode into its parent is accepted
// when the merged block stays small or adds few explicit zeros.
bool accept_merge(int columns, double zero_fraction) {
  if (columns <= 4) return true;
  if (columns <= 16) return zero_fraction < 0.8;
  if (columns <= 48) return zero_fraction < 0.1;
  return zero_fraction < 0.05;
}

// Below this many multiply-adds in all fronts the factorisation runs on one thread (the subtrees
// would be too small to be worth a thread each).
constexpr double kMinParallelFactorWork = 2e7 + 1;

double trapezoid(double columns, double rows_below) { return columns * (columns + 1.0) / 2.0 + columns * rows_below; }

}  // namespace

void SupernodalCholesky::analyze(const SparseMatrix& pattern) {
  if (pattern.rows() != pattern.cols()) throw std::invalid_argument("SupernodalCholesky: matrix is not square");
  factorized_ = false;
  n_ = pattern.rows();
  const int n = static_cast<int>(n_);
  const auto at = [](std::vector<int>& v, int i) -> int& { return v[static_cast<std::size_t>(i)]; };

  // Elimination tree in the caller's order (Liu 1986, with path compression).
  std::vector<int> caller_parent(static_cast<std::size_t>(n), -1), ancestor(static_cast<std::size_t>(n), -1);
  for (int k = 0; k < n; ++k)
    for (SparseMatrix::InnerIterator it(pattern, k); it; ++it) {
      int i = static_cast<int>(it.row());
      while (i != -1 && i < k) {
        const int next = at(ancestor, i);
        at(ancestor, i) = k;
        if (next == -1) at(caller_parent, i) = k;
        i = next;
      }
    }

  // Postorder (children visited in increasing index order, roots likewise).
  std::vector<int> first_child(static_cast<std::size_t>(n), -1), next_sibling(static_cast<std::size_t>(n), -1);
  for (int j = n - 1; j >= 0; --j) {
    const int p = at(caller_parent, j);
    if (p != -1) {
      at(next_sibling, j) = at(first_child, p);
      at(first_child, p) = j;
    }
  }
  to_caller_.clear();
  to_caller_.reserve(static_cast<std::size_t>(n));
  std::vector<int> stack;
  for (int root = 0; root < n; ++root) {
    if (at(caller_parent, root) != -1) continue;
    stack.push_back(root);
    while (!stack.empty()) {
      const int top = stack.back();
      const int child = at(first_child, top);
      if (child != -1) {
        at(first_child, top) = at(next_sibling, child);  // consume the child
        stack.push_back(child);
      } else {
        to_caller_.push_back(top);
        stack.pop_back();
      }
    }
  }
  from_caller_.assign(static_cast<std::size_t>(n), 0);
  for (int j = 0; j < n; ++j) at(from_caller_, at(to_caller_, j)) = j;
  std::vector<int> parent(static_cast<std::size_t>(n), -1), child_count(static_cast<std::size_t>(n), 0);
  for (int j = 0; j < n; ++j) {
    const int p = at(caller_parent, at(to_caller_, j));
    at(parent, j) = p == -1 ? -1 : at(from_caller_, p);
    if (p != -1) ++at(child_count, at(parent, j));
  }

  // Column counts of L (row-subtree traversal, internal order).
  std::vector<int> column_count(static_cast<std::size_t>(n), 1), mark(static_cast<std::size_t>(n), -1);
  for (int k = 0; k < n; ++k) {
    at(mark, k) = k;
    for (SparseMatrix::InnerIterator it(pattern, at(to_caller_, k)); it; ++it) {
      int i = at(from_caller_, static_cast<int>(it.row()));
      while (i < k && at(mark, i) != k) {
        ++at(column_count, i);
        at(mark, i) = k;
        i = at(parent, i);
      }
    }
  }

  // Fundamental supernodes (chains of single children with nested structure), width-capped.
  std::vector<int> first, width;
  for (int j = 0; j < n; ++j) {
    const bool extends = j > 0 && at(parent, j - 1) == j && at(column_count, j - 1) == at(column_count, j) + 1 &&
                         at(child_count, j) == 1;
    if (extends) {
      ++width.back();
    } else {
      first.push_back(j);
      width.push_back(1);
    }
  }
  const int fundamental = static_cast<int>(first.size());
  std::vector<int> supernode_of(static_cast<std::size_t>(n));
  for (int s = 0; s < fundamental; ++s)
    for (int c = first[static_cast<std::size_t>(s)]; c < first[static_cast<std::size_t>(s)] + width[static_cast<std::size_t>(s)]; ++c)
      at(supernode_of, c) = s;
  std::vector<int> rows_below(static_cast<std::size_t>(fundamental)), super_parent(static_cast<std::size_t>(fundamental));
  std::vector<double> true_entries(static_cast<std::size_t>(fundamental)), stored_entries(static_cast<std::size_t>(fundamental));
  for (int s = 0; s < fundamental; ++s) {
    const std::size_t u = static_cast<std::size_t>(s);
    rows_below[u] = at(column_count, first[u]) - width[u];
    const int last_parent = at(parent, first[u] + width[u] - 1);
    super_parent[u] = last_parent == -1 ? -1 : at(supernode_of, last_parent);
    true_entries[u] = stored_entries[u] = trapezoid(width[u], rows_below[u]);
  }

  // Relaxed amalgamation: a supernode merges into its parent when it directly precedes it (so
  // the columns stay contiguous) and accept_merge agrees. The merged rows below are the parent's.
  std::vector<int> merged_into(static_cast<std::size_t>(fundamental), -1);
  for (int s = 0; s < fundamental; ++s) {
    const std::size_t u = static_cast<std::size_t>(s);
    const int p = super_parent[u];
    if (p == -1) continue;
    const std::size_t w = static_cast<std::size_t>(p);
    if (first[u] + width[u] != first[w]) continue;
    const int columns = width[u] + width[w];
    const double stored = trapezoid(columns, rows_below[w]);
    const double real = true_entries[u] + true_entries[w];
    if (!accept_merge(columns, (stored - real) / stored)) continue;
    first[w] = first[u];
    width[w] = columns;
    true_entries[w] = real;
    stored_entries[w] = stored;
    merged_into[u] = p;
  }
  first_column_.clear();
  for (int s = 0; s < fundamental; ++s)
    if (merged_into[static_cast<std::size_t>(s)] == -1) first_column_.push_back(first[static_cast<std::size_t>(s)]);
  first_column_.push_back(n);
  const int supernodes = static_cast<int>(first_column_.size()) - 1;
  for (int s = 0; s < supernodes; ++s)
    for (int c = first_column_[static_cast<std::size_t>(s)]; c < first_column_[static_cast<std::size_t>(s) + 1]; ++c) at(supernode_of, c) = s;
  parent_supernode_.assign(static_cast<std::size_t>(supernodes), -1);
  for (int s = 0; s < supernodes; ++s) {
    const int p = at(parent, first_column_[static_cast<std::size_t>(s) + 1] - 1);
    parent_supernode_[static_cast<std::size_t>(s)] = p == -1 ? -1 : at(supernode_of, p);
  }

  // Row structures below each supernode: A's entries below its columns plus its children's rows.
  std::vector<std::vector<int>> children(static_cast<std::size_t>(supernodes));
  for (int s = 0; s < supernodes; ++s)
    if (parent_supernode_[static_cast<std::size_t>(s)] != -1) children[static_cast<std::size_t>(parent_supernode_[static_cast<std::size_t>(s)])].push_back(s);
  row_start_.assign(1, 0);
  row_indices_.clear();
  std::fill(mark.begin(), mark.end(), -1);
  std::vector<int> rows;
  for (int s = 0; s < supernodes; ++s) {
    const int begin = first_column_[static_cast<std::size_t>(s)], end = first_column_[static_cast<std::size_t>(s) + 1];
    rows.clear();
    for (int c = begin; c < end; ++c)
      for (SparseMatrix::InnerIterator it(pattern, at(to_caller_, c)); it; ++it) {
        const int i = at(from_caller_, static_cast<int>(it.row()));
        if (i >= end && at(mark, i) != s) {
          at(mark, i) = s;
          rows.push_back(i);
        }
      }
    for (int child : children[static_cast<std::size_t>(s)])
      for (int k = row_start_[static_cast<std::size_t>(child)]; k < row_start_[static_cast<std::size_t>(child) + 1]; ++k) {
        const int i = row_indices_[static_cast<std::size_t>(k)];
        if (i >= end && at(mark, i) != s) {
          at(mark, i) = s;
          rows.push_back(i);
        }
      }
    std::sort(rows.begin(), rows.end());
    row_indices_.insert(row_indices_.end(), rows.begin(), rows.end());
    row_start_.push_back(static_cast<int>(row_indices_.size()));
  }

  child_start_.assign(static_cast<std::size_t>(supernodes) + 1, 0);
  child_list_.clear();
  for (int s = 0; s < supernodes; ++s) {
    child_list_.insert(child_list_.end(), children[static_cast<std::size_t>(s)].begin(), children[static_cast<std::size_t>(s)].end());
    child_start_[static_cast<std::size_t>(s) + 1] = static_cast<int>(child_list_.size());
  }
  plan_threads(thread_count_);

  value_start_.assign(static_cast<std::size_t>(supernodes) + 1, 0);
  stored_nonzeros_ = 0.0;
  for (int s = 0; s < supernodes; ++s) {
    const std::size_t u = static_cast<std::size_t>(s);
    const std::size_t k = static_cast<std::size_t>(first_column_[u + 1] - first_column_[u]);
    const std::size_t r = static_cast<std::size_t>(row_start_[u + 1] - row_start_[u]);
    value_start_[u + 1] = value_start_[u] + (k + r) * k;
    stored_nonzeros_ += trapezoid(static_cast<double>(k), static_cast<double>(r));
  }
  values_.assign(value_start_.back(), 0.0);
}

void SupernodalCholesky::set_thread_count(int threads) {
  if (threads < 1) throw std::invalid_argument("SupernodalCholesky: thread count must be >= 1");
  thread_count_ = threads;
  if (!first_column_.empty()) plan_threads(thread_count_);
}

void SupernodalCholesky::plan_threads(int threads) {
  const int supernodes = supernode_count();
  thread_lists_.clear();
  top_list_.clear();
  // Work of a front: about k (k + r)^2 multiply-adds; summed over subtrees.
  std::vector<double> subtree(static_cast<std::size_t>(supernodes), 0.0);
  double total = 0.0;
  for (int s = 0; s < supernodes; ++s) {
    const std::size_t u = static_cast<std::size_t>(s);
    const double k = first_column_[u + 1] - first_column_[u], r = row_start_[u + 1] - row_start_[u];
    subtree[u] += k * (k + r) * (k + r);
    total += k * (k + r) * (k + r);
    if (parent_supernode_[u] != -1) subtree[static_cast<std::size_t>(parent_supernode_[u])] += subtree[u];
  }
  std::vector<int> owner(static_cast<std::size_t>(supernodes), -1);
  if (execution_policy(threads, total, kMinParallelFactorWork) == ExecutionPolicy::parallel) {
    // Open the heaviest subtree until it no longer exceeds half of the open subtrees' work.
    std::vector<int> open;
    for (int s = 0; s < supernodes; ++s)
      if (parent_supernode_[static_cast<std::size_t>(s)] == -1) open.push_back(s);
    for (int round = 0; round < 64 && !open.empty(); ++round) {
      std::size_t heaviest = 0;
      double sum = 0.0;
      for (std::size_t q = 0; q < open.size(); ++q) {
        sum += subtree[static_cast<std::size_t>(open[q])];
        if (subtree[static_cast<std::size_t>(open[q])] > subtree[static_cast<std::size_t>(open[heaviest])]) heaviest = q;
      }
      if (subtree[static_cast<std::size_t>(open[heaviest])] <= 0.5 * sum) break;
      const std::size_t h = static_cast<std::size_t>(open[heaviest]);
      open.erase(open.begin() + static_cast<std::ptrdiff_t>(heaviest));
      open.insert(open.end(), child_list_.begin() + child_start_[h], child_list_.begin() + child_start_[h + 1]);
      std::sort(open.begin(), open.end());
    }
    // Longest-processing-time assignment of the open subtrees to the threads.
    std::vector<int> by_work = open;
    std::stable_sort(by_work.begin(), by_work.end(), [&](int a, int b) { return subtree[static_cast<std::size_t>(a)] > subtree[static_cast<std::size_t>(b)]; });
    std::vector<double> load(static_cast<std::size_t>(threads), 0.0);
    for (int root : by_work) {
      const std::size_t t = static_cast<std::size_t>(std::min_element(load.begin(), load.end()) - load.begin());
      load[t] += subtree[static_cast<std::size_t>(root)];
      owner[static_cast<std::size_t>(root)] = static_cast<int>(t);
    }
    // Descendants inherit their subtree root's thread (parents have larger indices); the opened
    // nodes above the roots keep -1 and go to the main thread afterwards.
    for (int s = supernodes - 1; s >= 0; --s) {
      const int p = parent_supernode_[static_cast<std::size_t>(s)];
      if (owner[static_cast<std::size_t>(s)] == -1 && p != -1) owner[static_cast<std::size_t>(s)] = owner[static_cast<std::size_t>(p)];
    }
    thread_lists_.assign(static_cast<std::size_t>(threads), {});
  } else {
    thread_lists_.assign(1, {});
  }
  for (int s = 0; s < supernodes; ++s) {
    const int t = owner[static_cast<std::size_t>(s)];
    if (t >= 0) thread_lists_[static_cast<std::size_t>(t)].push_back(s);
    else top_list_.push_back(s);
  }
}

bool SupernodalCholesky::factor_supernode(int s, const SparseMatrix& A, Workspace& work,
                                          std::vector<std::vector<double>>& updates, WorkerPool* split_pool) {
  const std::size_t u = static_cast<std::size_t>(s);
  const int begin = first_column_[u], end = first_column_[u + 1];
  const int k = end - begin;
  const int r = row_start_[u + 1] - row_start_[u];
  const int m = k + r;
  const int* below = row_indices_.data() + row_start_[u];
  std::vector<int>& local = work.local;
  if (local.size() != static_cast<std::size_t>(n_)) local.assign(static_cast<std::size_t>(n_), -1);
  if (work.front.size() < static_cast<std::size_t>(m) * static_cast<std::size_t>(m)) work.front.resize(static_cast<std::size_t>(m) * static_cast<std::size_t>(m));
  Eigen::Map<Eigen::MatrixXd> F(work.front.data(), m, m);
  for (int c = 0; c < m; ++c) F.col(c).tail(m - c).setZero();  // the lower triangle is all that is used
  for (int c = begin; c < end; ++c) local[static_cast<std::size_t>(c)] = c - begin;
  for (int a = 0; a < r; ++a) local[static_cast<std::size_t>(below[a])] = k + a;

  for (int c = begin; c < end; ++c)
    for (SparseMatrix::InnerIterator it(A, to_caller_[static_cast<std::size_t>(c)]); it; ++it) {
      const int i = from_caller_[static_cast<std::size_t>(it.row())];
      if (i >= c) F(local[static_cast<std::size_t>(i)], c - begin) += it.value();
    }
  // Extend-add the children's update matrices, in increasing child order (a fixed summation
  // order whichever thread produced them).
  for (int q = child_start_[u]; q < child_start_[u + 1]; ++q) {
    const std::size_t child = static_cast<std::size_t>(child_list_[static_cast<std::size_t>(q)]);
    const int rc = row_start_[child + 1] - row_start_[child];
    const int* child_rows = row_indices_.data() + row_start_[child];
    const double* U = updates[child].data();  // packed lower columns
    for (int b = 0; b < rc; ++b) {
      double* column = &F(0, local[static_cast<std::size_t>(child_rows[b])]);
      for (int a = b; a < rc; ++a) column[local[static_cast<std::size_t>(child_rows[a])]] += *U++;
    }
    std::vector<double>().swap(updates[child]);
  }

  // Dense partial factorisation of the front, right-looking in panels of at most kPanelWidth
  // columns: every kernel's inner dimension is a panel width, which keeps the summation order
  // independent of Eigen's cache-size-dependent blocking.
  bool ok = true;
  for (int p = 0; p < k && ok; p += kPanelWidth) {
    const int b = std::min(kPanelWidth, k - p);
    const int rest = m - p - b;
    Eigen::Ref<Eigen::MatrixXd> diagonal = F.block(p, p, b, b);
    Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>, Eigen::Lower> llt(diagonal);
    if (llt.info() != Eigen::Success) ok = false;
    if (!ok || rest == 0) continue;
    auto panel = F.block(p + b, p, rest, b);
    diagonal.triangularView<Eigen::Lower>().transpose().solveInPlace<Eigen::OnTheRight>(panel);
    auto trailing = F.block(p + b, p + b, rest, rest);
    if (rest < kSplitUpdate) {
      trailing.selfadjointView<Eigen::Lower>().rankUpdate(panel, -1.0);
      continue;
    }
    // Large trailing updates are always cut in the same two parts of about equal work (columns
    // before and after 30% of the width), whether or not a second thread takes one of them, so
    // the result is the same for any thread count.
    const int cut = rest * 3 / 10;
    auto left_part = [&] {
      trailing.topLeftCorner(cut, cut).selfadjointView<Eigen::Lower>().rankUpdate(panel.topRows(cut), -1.0);
      trailing.bottomLeftCorner(rest - cut, cut).noalias() -= panel.bottomRows(rest - cut) * panel.topRows(cut).transpose();
    };
    auto right_part = [&] {
      trailing.bottomRightCorner(rest - cut, rest - cut).selfadjointView<Eigen::Lower>().rankUpdate(panel.bottomRows(rest - cut), -1.0);
    };
    if (split_pool) {
      split_pool->run_parts(2, [&](int part) { part == 0 ? left_part() : right_part(); });
    } else {
      left_part();
      right_part();
    }
  }
  if (ok && r > 0) {
    std::vector<double>& update = updates[u];
    update.clear();
    update.reserve(static_cast<std::size_t>(r) * static_cast<std::size_t>(r + 1) / 2);
    for (int b = 0; b < r; ++b) {
      const double* column = work.front.data() + static_cast<std::size_t>(k + b) * static_cast<std::size_t>(m) + static_cast<std::size_t>(k + b);
      update.insert(update.end(), column, column + (r - b));
    }
  }
  if (ok) Eigen::Map<Eigen::MatrixXd>(values_.data() + value_start_[u], m, k) = F.leftCols(k);
  for (int c = begin; c < end; ++c) local[static_cast<std::size_t>(c)] = -1;
  for (int a = 0; a < r; ++a) local[static_cast<std::size_t>(below[a])] = -1;
  return ok;
}

bool SupernodalCholesky::factorize(const SparseMatrix& A) {
  factorized_ = false;
  if (A.rows() != n_ || A.cols() != n_) throw std::invalid_argument("SupernodalCholesky: matrix size differs from the analysed one");
  const int supernodes = supernode_count();
  std::vector<std::vector<double>> updates(static_cast<std::size_t>(supernodes));
  // Independent subtrees first, one list per thread (a partition fixed by analyze(); the
  // numbers computed do not depend on it), then the remaining top of the tree.
  const int threads = static_cast<int>(thread_lists_.size());
  std::vector<Workspace> workspaces(static_cast<std::size_t>(std::max(threads, 1)));
  std::vector<char> failed(static_cast<std::size_t>(std::max(threads, 1)), 0);
  auto run_list = [&](int t) {
    try {
      for (int s : thread_lists_[static_cast<std::size_t>(t)])
        if (!factor_supernode(s, A, workspaces[static_cast<std::size_t>(t)], updates, nullptr)) {
          failed[static_cast<std::size_t>(t)] = 1;
          return;
        }
    } catch (...) {
      failed[static_cast<std::size_t>(t)] = 2;
    }
  };
  // One pool for the subtree lists and the top's split updates; with fewer threads than lists
  // (the system refused some) a thread runs several lists, one after another (the same numbers).
  WorkerPool pool(std::max({threads, thread_count_ > 1 ? 2 : 1, 1}));
  if (threads > 0) pool.run_parts(threads, run_list);
  for (char f : failed) {
    if (f == 2) throw std::runtime_error("SupernodalCholesky: a worker thread failed (out of memory?)");
    if (f == 1) return false;
  }
  // The top of the tree holds the largest fronts: their trailing updates use the second thread.
  for (int s : top_list_)
    if (!factor_supernode(s, A, workspaces[0], updates, thread_count_ > 1 ? &pool : nullptr)) return false;
  factorized_ = true;
  return true;
}

BlockLdlt SupernodalCholesky::block_ldlt(int max_width) const {
  if (!factorized_) throw std::logic_error("SupernodalCholesky::block_ldlt without a successful factorisation");
  if (max_width < 1) throw std::invalid_argument("SupernodalCholesky::block_ldlt: max_width must be >= 1");
  BlockLdlt out;
  out.order = to_caller_;
  out.pivots.resize(static_cast<std::size_t>(n_));
  out.values.reserve(values_.size());
  const int supernodes = supernode_count();
  for (int s = 0; s < supernodes; ++s) {
    const std::size_t u = static_cast<std::size_t>(s);
    const int begin = first_column_[u], k = first_column_[u + 1] - begin, r = row_start_[u + 1] - row_start_[u];
    const Eigen::Map<const Eigen::MatrixXd> block(values_.data() + value_start_[u], k + r, k);
    for (int c = 0; c < k; ++c) out.pivots[static_cast<std::size_t>(begin + c)] = block(c, c) * block(c, c);
    // Runs of at most max_width columns: a run's rows below are the supernode's later columns,
    // then the supernode's rows below.
    for (int c0 = 0; c0 < k; c0 += max_width) {
      BlockLdlt::Supernode t;
      t.first = begin + c0;
      t.width = std::min(max_width, k - c0);
      t.row_begin = static_cast<int>(out.rows.size());
      t.row_count = k - c0 - t.width + r;
      for (int i = c0 + t.width; i < k; ++i) out.rows.push_back(begin + i);
      out.rows.insert(out.rows.end(), row_indices_.begin() + row_start_[u], row_indices_.begin() + row_start_[u + 1]);
      t.triangle = out.values.size();
      for (int i = 1; i < t.width; ++i)
        for (int j = 0; j < i; ++j) out.values.push_back(block(c0 + i, c0 + j) / block(c0 + j, c0 + j));
      t.below = out.values.size();
      for (int i = c0 + t.width; i < k + r; ++i)
        for (int j = 0; j < t.width; ++j) out.values.push_back(block(i, c0 + j) / block(c0 + j, c0 + j));
      out.supernodes.push_back(t);
    }
  }
  return out;
}

void SupernodalCholesky::solve_in_place(Eigen::MatrixXd& B) const {
  if (!factorized_) throw std::logic_error("SupernodalCholesky::solve_in_place without a successful factorisation");
  if (B.rows() != n_) throw std::invalid_argument("SupernodalCholesky: right-hand side has the wrong number of rows");
  const Eigen::Index nrhs = B.cols();
  Eigen::MatrixXd X(n_, nrhs);
  for (Eigen::Index j = 0; j < n_; ++j) X.row(j) = B.row(to_caller_[static_cast<std::size_t>(j)]);
  const int supernodes = supernode_count();
  // As in factorize(), every product's inner dimension is cut into chunks of at most
  // kPanelWidth, summed in a fixed order, so no cache-dependent blocking changes the rounding.
  Eigen::MatrixXd scratch, gathered;
  for (int s = 0; s < supernodes; ++s) {  // L y = b
    const std::size_t u = static_cast<std::size_t>(s);
    const int begin = first_column_[u], k = first_column_[u + 1] - begin, r = row_start_[u + 1] - row_start_[u];
    const Eigen::Map<const Eigen::MatrixXd> block(values_.data() + value_start_[u], k + r, k);
    auto Xs = X.middleRows(begin, k);
    for (int p = 0; p < k; p += kPanelWidth) {
      const int b = std::min(kPanelWidth, k - p);
      auto panel_rows = Xs.middleRows(p, b);
      block.block(p, p, b, b).triangularView<Eigen::Lower>().solveInPlace(panel_rows);
      if (p + b < k) Xs.middleRows(p + b, k - p - b).noalias() -= block.block(p + b, p, k - p - b, b) * panel_rows;
    }
    if (r == 0) continue;
    scratch.setZero(r, nrhs);
    for (int p = 0; p < k; p += kPanelWidth) {
      const int b = std::min(kPanelWidth, k - p);
      scratch.noalias() += block.block(k, p, r, b) * Xs.middleRows(p, b);
    }
    const int* below = row_indices_.data() + row_start_[u];
    for (int a = 0; a < r; ++a) X.row(below[a]) -= scratch.row(a);
  }
  for (int s = supernodes - 1; s >= 0; --s) {  // L^T x = y
    const std::size_t u = static_cast<std::size_t>(s);
    const int begin = first_column_[u], k = first_column_[u + 1] - begin, r = row_start_[u + 1] - row_start_[u];
    const Eigen::Map<const Eigen::MatrixXd> block(values_.data() + value_start_[u], k + r, k);
    auto Xs = X.middleRows(begin, k);
    if (r > 0) {
      const int* below = row_indices_.data() + row_start_[u];
      gathered.resize(r, nrhs);
      for (int a = 0; a < r; ++a) gathered.row(a) = X.row(below[a]);
      for (int q = 0; q < r; q += kPanelWidth) {
        const int b = std::min(kPanelWidth, r - q);
        Xs.noalias() -= block.block(k + q, 0, b, k).transpose() * gathered.middleRows(q, b);
      }
    }
    for (int p = ((k - 1) / kPanelWidth) * kPanelWidth; p >= 0; p -= kPanelWidth) {
      const int b = std::min(kPanelWidth, k - p);
      auto panel_rows = Xs.middleRows(p, b);
      for (int q = p + b; q < k; q += kPanelWidth) {
        const int c = std::min(kPanelWidth, k - q);
        panel_rows.noalias() -= block.block(q, p, c, b).transpose() * Xs.middleRows(q, c);
      }
      block.block(p, p, b, b).triangularView<Eigen::Lower>().transpose().solveInPlace(panel_rows);
    }
  }
  for (Eigen::Index j = 0; j < n_; ++j) B.row(to_caller_[static_cast<std::size_t>(j)]) = X.row(j);
}

}  // namespace offsetopt
