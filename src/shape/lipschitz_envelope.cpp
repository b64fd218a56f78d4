#include "shape/lipschitz_envelope.h"

#include <set>
#include <utility>
#include <vector>

namespace offsetopt {

Eigen::VectorXd lipschitz_envelope(const Mesh& mesh, const Eigen::VectorXd& values, double slope) {
  const Eigen::Index n = mesh.V.rows();
  std::vector<std::vector<std::pair<int, double>>> neighbours(static_cast<std::size_t>(n));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int a = mesh.F(f, c), b = mesh.F(f, (c + 1) % 3);
      const double length = (mesh.V.row(a) - mesh.V.row(b)).norm() * slope;
      neighbours[static_cast<std::size_t>(a)].emplace_back(b, length);
      neighbours[static_cast<std::size_t>(b)].emplace_back(a, length);
    }
  Eigen::VectorXd out = values;
  std::set<std::pair<double, int>> queue;
  for (Eigen::Index i = 0; i < n; ++i) queue.emplace(out(i), static_cast<int>(i));
  while (!queue.empty()) {
    const auto [value, i] = *queue.begin();
    queue.erase(queue.begin());
    for (const auto& [j, length] : neighbours[static_cast<std::size_t>(i)]) {
      if (value + length < out(j)) {
        queue.erase({out(j), j});
        out(j) = value + length;
        queue.emplace(out(j), j);
      }
    }
  }
  return out;
}

}  // namespace offsetopt
