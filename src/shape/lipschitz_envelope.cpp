#include "shape/lipschitz_envelope.h"

#include <functional>
#include <queue>
#include <utility>
#include <vector>

namespace offsetopt {

Eigen::VectorXd lipschitz_envelope(const Mesh& mesh, const Eigen::VectorXd& values, double slope) {
  const Eigen::Index n = mesh.V.rows();
  // The edge graph in compressed rows (each face edge both ways: at 10^6 vertices, one vector per
  // vertex cost more than the search).
  std::vector<int> start(static_cast<std::size_t>(n) + 1, 0);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      ++start[static_cast<std::size_t>(mesh.F(f, c)) + 1];
      ++start[static_cast<std::size_t>(mesh.F(f, (c + 1) % 3)) + 1];
    }
  for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i) start[i + 1] += start[i];
  std::vector<std::pair<int, double>> neighbours(static_cast<std::size_t>(start.back()));
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int a = mesh.F(f, c), b = mesh.F(f, (c + 1) % 3);
      const double length = (mesh.V.row(a) - mesh.V.row(b)).norm() * slope;
      neighbours[static_cast<std::size_t>(fill[static_cast<std::size_t>(a)]++)] = {b, length};
      neighbours[static_cast<std::size_t>(fill[static_cast<std::size_t>(b)]++)] = {a, length};
    }
  // Dijkstra with a binary heap; an entry whose value is above the vertex's current one is stale.
  // Adding a length >= 0 is monotone and never lowers a value, so every vertex is final when first
  // popped at its value, and the result is the minimum over paths whatever the order of ties.
  Eigen::VectorXd out = values;
  using Entry = std::pair<double, int>;
  std::vector<Entry> heap;
  heap.reserve(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) heap.emplace_back(out(i), static_cast<int>(i));
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue(std::greater<Entry>(), std::move(heap));
  while (!queue.empty()) {
    const auto [value, i] = queue.top();
    queue.pop();
    if (value > out(i)) continue;
    for (int e = start[static_cast<std::size_t>(i)]; e < start[static_cast<std::size_t>(i) + 1]; ++e) {
      const auto& [j, length] = neighbours[static_cast<std::size_t>(e)];
      if (value + length < out(j)) {
        out(j) = value + length;
        queue.emplace(out(j), j);
      }
    }
  }
  return out;
}

}  // namespace offsetopt
