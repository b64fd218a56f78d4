#include "sparse/fill_reducing_ordering.h"

#include <exception>
#include <stdexcept>

#include "sparse/minimum_degree_ordering.h"
#include "sparse/nested_dissection.h"
#include "util/parallel.h"

namespace offsetopt {

using SparseMatrix = Eigen::SparseMatrix<double>;

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

FillReducingOrdering fill_reducing_ordering(const SparseMatrix& pattern, const Vertices& positions, const SparseMatrix& graph,
                                           int hops, bool second_thread) {
  const bool try_dissection = positions.rows() == pattern.rows() && graph.rows() == pattern.rows() && hops >= 1;
  // The two candidates are independent: with `second_thread` nested dissection runs beside the
  // minimum-degree ordering (the pool runs both parts on this thread when it gets no other).
  FillReducingOrdering nd, amd;
  bool dissection_failed = false;
  std::exception_ptr amd_error;
  WorkerPool pool(try_dissection && second_thread ? 2 : 1);
  pool.run_parts(try_dissection ? 2 : 1, [&](int part) {
    try {
      if (part == 0) {
        amd.method = "amd";
        amd.new_to_old = minimum_degree_ordering(pattern);
        amd.counts = cholesky_counts(pattern, amd.new_to_old);
      } else {
        nd.method = "nested_dissection";
        nd.new_to_old = nested_dissection(pattern, positions, graph, hops);
        nd.counts = cholesky_counts(pattern, nd.new_to_old);
      }
    } catch (...) {
      if (part == 0) amd_error = std::current_exception();
      else dissection_failed = true;
    }
  });
  if (amd_error) std::rethrow_exception(amd_error);
  if (dissection_failed) throw std::runtime_error("fill_reducing_ordering: nested dissection failed (out of memory?)");
  if (!try_dissection) return amd;
  return nd.counts.flops < amd.counts.flops ? nd : amd;
}

}  // namespace offsetopt
