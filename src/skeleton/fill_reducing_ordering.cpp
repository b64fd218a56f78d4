#include "skeleton/fill_reducing_ordering.h"

#include <Eigen/OrderingMethods>
#include <algorithm>
#include <numeric>

namespace offsetopt {

namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

std::vector<int> amd_order(const SparseMatrix& pattern) {
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> new_to_old;
  Eigen::AMDOrdering<int> amd;
  amd(pattern, new_to_old);
  return std::vector<int>(new_to_old.indices().data(), new_to_old.indices().data() + new_to_old.size());
}

// AMD restricted to the submatrix of `ids` (sorted), appended to `order`.
void append_amd(const SparseMatrix& pattern, const std::vector<int>& ids, std::vector<int>& local, std::vector<int>& order) {
  if (ids.size() <= 2) {
    order.insert(order.end(), ids.begin(), ids.end());
    return;
  }
  for (std::size_t k = 0; k < ids.size(); ++k) local[static_cast<std::size_t>(ids[k])] = static_cast<int>(k);
  std::vector<Eigen::Triplet<double>> entries;
  for (std::size_t k = 0; k < ids.size(); ++k)
    for (SparseMatrix::InnerIterator it(pattern, ids[k]); it; ++it)
      if (local[static_cast<std::size_t>(it.row())] >= 0) entries.emplace_back(local[static_cast<std::size_t>(it.row())], static_cast<int>(k), 1.0);
  SparseMatrix sub(static_cast<Eigen::Index>(ids.size()), static_cast<Eigen::Index>(ids.size()));
  sub.setFromTriplets(entries.begin(), entries.end());
  for (int i : ids) local[static_cast<std::size_t>(i)] = -1;
  for (int k : amd_order(sub)) order.push_back(ids[static_cast<std::size_t>(k)]);
}

class NestedDissection {
 public:
  NestedDissection(const SparseMatrix& pattern, const Vertices& positions)
      : pattern_(pattern), positions_(positions), side_(static_cast<std::size_t>(pattern.rows()), 0),
        local_(static_cast<std::size_t>(pattern.rows()), -1) {}

  std::vector<int> run() {
    std::vector<int> all(static_cast<std::size_t>(pattern_.rows()));
    std::iota(all.begin(), all.end(), 0);
    order_.reserve(all.size());
    dissect(all, 0);
    return order_;
  }

 private:
  static constexpr std::size_t kLeafSize = 256;

  void dissect(std::vector<int> ids, int depth) {
    if (ids.size() <= kLeafSize || depth > 48) {
      std::sort(ids.begin(), ids.end());
      append_amd(pattern_, ids, local_, order_);
      return;
    }
    const std::size_t middle = ids.size() / 2;
    std::vector<int> best_first, best_second, best_separator;
    bool have_best = false;
    for (int axis = 0; axis < 3; ++axis) {
      std::vector<int> sorted = ids;
      std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(middle), sorted.end(), [&](int a, int b) {
        const double pa = positions_(a, axis), pb = positions_(b, axis);
        return pa < pb || (pa == pb && a < b);
      });
      for (std::size_t k = 0; k < sorted.size(); ++k) side_[static_cast<std::size_t>(sorted[k])] = k < middle ? 1 : 2;
      // Boundary of each half in the matrix graph; the smaller one becomes the separator.
      std::vector<int> inner_low, boundary_low, inner_high, boundary_high;
      for (std::size_t k = 0; k < sorted.size(); ++k) {
        const int i = sorted[k];
        const int other = k < middle ? 2 : 1;
        bool on_boundary = false;
        for (SparseMatrix::InnerIterator it(pattern_, i); it; ++it)
          if (side_[static_cast<std::size_t>(it.row())] == other) {
            on_boundary = true;
            break;
          }
        if (k < middle) (on_boundary ? boundary_low : inner_low).push_back(i);
        else (on_boundary ? boundary_high : inner_high).push_back(i);
      }
      for (int i : sorted) side_[static_cast<std::size_t>(i)] = 0;
      const bool low_is_separator = boundary_low.size() <= boundary_high.size();
      std::vector<int>& separator = low_is_separator ? boundary_low : boundary_high;
      if (!have_best || separator.size() < best_separator.size()) {
        have_best = true;
        if (low_is_separator) {
          best_first = inner_low;
          best_second.assign(sorted.begin() + static_cast<std::ptrdiff_t>(middle), sorted.end());
        } else {
          best_first.assign(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(middle));
          best_second = inner_high;
        }
        best_separator = separator;
      }
    }
    dissect(std::move(best_first), depth + 1);
    dissect(std::move(best_second), depth + 1);
    std::sort(best_separator.begin(), best_separator.end());
    append_amd(pattern_, best_separator, local_, order_);
  }

  const SparseMatrix& pattern_;
  const Vertices& positions_;
  std::vector<int> side_;
  std::vector<int> local_;
  std::vector<int> order_;
};

}  // namespace

CholeskyCounts cholesky_counts(const SparseMatrix& pattern, const std::vector<int>& new_to_old) {
  const int n = static_cast<int>(pattern.rows());
  std::vector<int> old_to_new(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) old_to_new[static_cast<std::size_t>(new_to_old[static_cast<std::size_t>(k)])] = k;
  CholeskyCounts out;
  out.parent.assign(static_cast<std::size_t>(n), -1);
  out.column_counts.assign(static_cast<std::size_t>(n), 1);
  std::vector<int> ancestor(static_cast<std::size_t>(n), -1), mark(static_cast<std::size_t>(n), -1);
  // Elimination tree (Liu 1986), row by row of the permuted upper triangle, path compression.
  for (int k = 0; k < n; ++k) {
    for (SparseMatrix::InnerIterator it(pattern, new_to_old[static_cast<std::size_t>(k)]); it; ++it) {
      int i = old_to_new[static_cast<std::size_t>(it.row())];
      while (i != -1 && i < k) {
        const int next = ancestor[static_cast<std::size_t>(i)];
        ancestor[static_cast<std::size_t>(i)] = k;
        if (next == -1) out.parent[static_cast<std::size_t>(i)] = k;
        i = next;
      }
    }
  }
  // Row k of L is the union of the tree paths from each i < k in A's row k up to k.
  for (int k = 0; k < n; ++k) {
    mark[static_cast<std::size_t>(k)] = k;
    for (SparseMatrix::InnerIterator it(pattern, new_to_old[static_cast<std::size_t>(k)]); it; ++it) {
      int i = old_to_new[static_cast<std::size_t>(it.row())];
      while (i < k && mark[static_cast<std::size_t>(i)] != k) {
        ++out.column_counts[static_cast<std::size_t>(i)];
        mark[static_cast<std::size_t>(i)] = k;
        i = out.parent[static_cast<std::size_t>(i)];
      }
    }
  }
  for (int c : out.column_counts) {
    out.flops += static_cast<double>(c) * static_cast<double>(c);
    out.nonzeros += c;
  }
  return out;
}

FillReducingOrdering fill_reducing_ordering(const SparseMatrix& pattern, const Vertices& positions) {
  FillReducingOrdering amd;
  amd.method = "amd";
  amd.new_to_old = amd_order(pattern);
  amd.counts = cholesky_counts(pattern, amd.new_to_old);
  if (positions.rows() != pattern.rows()) return amd;
  FillReducingOrdering nd;
  nd.method = "nested_dissection";
  nd.new_to_old = NestedDissection(pattern, positions).run();
  nd.counts = cholesky_counts(pattern, nd.new_to_old);
  return nd.counts.flops < amd.counts.flops ? nd : amd;
}

}  // namespace offsetopt
