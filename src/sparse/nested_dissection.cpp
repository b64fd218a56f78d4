#include "sparse/nested_dissection.h"

#include <algorithm>
#include <cstdint>
#include <numeric>

#include "sparse/minimum_degree_ordering.h"

namespace offsetopt {

namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

// Minimum degree restricted to the submatrix of `ids` (sorted), appended to `order`.
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
  for (int k : minimum_degree_ordering(sub)) order.push_back(ids[static_cast<std::size_t>(k)]);
}

// Geometric nested dissection on `graph` (the mesh's 1-ring graph) for a matrix whose pattern
// links vertices up to `hops` apart (2 for L^T L): a separator is the band of one half within
// `hops` steps of the other.
class NestedDissection {
 public:
  NestedDissection(const SparseMatrix& pattern, const SparseMatrix& graph, int hops, const Vertices& positions)
      : pattern_(pattern), graph_(graph), hops_(hops), positions_(positions), side_(static_cast<std::size_t>(graph.rows()), 0),
        local_(static_cast<std::size_t>(graph.rows()), -1), key_(static_cast<std::size_t>(graph.rows()), 0.0) {}

  std::vector<int> run() {
    std::vector<int> all(static_cast<std::size_t>(graph_.rows()));
    std::iota(all.begin(), all.end(), 0);
    order_.reserve(all.size());
    dissect(all, 0);
    return order_;
  }

 private:
  static constexpr std::size_t kLeafSize = 256;
  // The first cuts try 13 directions (axes, face and body diagonals), the others the 3 axes:
  // the top separators decide most of the fill.
  static constexpr int kManyDirectionsDepth = 3;
  static constexpr std::size_t kManyDirectionsSize = 4096;

  // Splits `ids` at the median along d and returns the separator: the vertices of the half with
  // fewer vertices next to the other half that lie within hops_ edges of it. On return side_
  // marks the halves 1 and 2 and the separator 3.
  std::vector<int> split(std::vector<int>& ids, std::size_t middle, const double* d) {
    for (int i : ids) key_[static_cast<std::size_t>(i)] = positions_(i, 0) * d[0] + positions_(i, 1) * d[1] + positions_(i, 2) * d[2];
    std::nth_element(ids.begin(), ids.begin() + static_cast<std::ptrdiff_t>(middle), ids.end(), [&](int a, int b) {
      const double pa = key_[static_cast<std::size_t>(a)], pb = key_[static_cast<std::size_t>(b)];
      return pa < pb || (pa == pb && a < b);
    });
    for (std::size_t k = 0; k < ids.size(); ++k) side_[static_cast<std::size_t>(ids[k])] = k < middle ? 1 : 2;
    // Vertices of each half with a neighbour in the other half: the first layer of a separator.
    std::vector<int> boundary[3];
    for (int i : ids) {
      const int mine = side_[static_cast<std::size_t>(i)];
      for (SparseMatrix::InnerIterator it(graph_, i); it; ++it) {
        const int other = side_[static_cast<std::size_t>(it.row())];
        if (other != 0 && other != mine) {
          boundary[mine].push_back(i);
          break;
        }
      }
    }
    const int separator_side = boundary[1].size() <= boundary[2].size() ? 1 : 2;
    std::vector<int> separator = std::move(boundary[separator_side]);
    for (int i : separator) side_[static_cast<std::size_t>(i)] = 3;
    // Further layers, hops_ in all, grown inside the separator's half.
    std::size_t layer_begin = 0;
    for (int hop = 1; hop < hops_; ++hop) {
      const std::size_t layer_end = separator.size();
      for (std::size_t k = layer_begin; k < layer_end; ++k)
        for (SparseMatrix::InnerIterator it(graph_, separator[k]); it; ++it) {
          const std::size_t j = static_cast<std::size_t>(it.row());
          if (side_[j] == separator_side) {
            side_[j] = 3;
            separator.push_back(static_cast<int>(j));
          }
        }
      layer_begin = layer_end;
    }
    return separator;
  }

  void dissect(std::vector<int> ids, int depth) {
    if (ids.size() <= kLeafSize || depth > 48) {
      std::sort(ids.begin(), ids.end());
      append_amd(pattern_, ids, local_, order_);
      return;
    }
    static const double directions[13][3] = {{1, 0, 0},  {0, 1, 0},  {0, 0, 1},  {1, 1, 0},  {1, -1, 0},
                                             {1, 0, 1},  {1, 0, -1}, {0, 1, 1},  {0, 1, -1}, {1, 1, 1},
                                             {1, 1, -1}, {1, -1, 1}, {-1, 1, 1}};
    const int direction_count = depth < kManyDirectionsDepth && ids.size() > kManyDirectionsSize ? 13 : 3;
    const std::size_t middle = ids.size() / 2;
    int best_direction = 0;
    std::size_t best_size = 0;
    for (int direction = 0; direction < direction_count; ++direction) {
      const std::size_t size = split(ids, middle, directions[direction]).size();
      if (direction == 0 || size < best_size) {
        best_size = size;
        best_direction = direction;
      }
      for (int i : ids) side_[static_cast<std::size_t>(i)] = 0;
    }
    std::vector<int> separator = split(ids, middle, directions[best_direction]);
    std::vector<int> first, second;
    for (int i : ids) {
      const int side = side_[static_cast<std::size_t>(i)];
      if (side == 1) first.push_back(i);
      else if (side == 2) second.push_back(i);
      side_[static_cast<std::size_t>(i)] = 0;
    }
    ids.clear();
    ids.shrink_to_fit();
    dissect(std::move(first), depth + 1);
    dissect(std::move(second), depth + 1);
    std::sort(separator.begin(), separator.end());
    append_amd(pattern_, separator, local_, order_);
  }

  const SparseMatrix& pattern_;
  const SparseMatrix& graph_;
  const int hops_;
  const Vertices& positions_;
  std::vector<std::uint8_t> side_;  // bytes: the random accesses of the cuts stay in cache
  std::vector<int> local_;
  std::vector<double> key_;
  std::vector<int> order_;
};

}  // namespace

std::vector<int> nested_dissection(const SparseMatrix& pattern, const Vertices& positions, const SparseMatrix& graph,
                                   int hops) {
  return NestedDissection(pattern, graph, hops, positions).run();
}

}  // namespace offsetopt
