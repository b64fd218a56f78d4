#include "shape/shrink_outer_limit.h"

#include "shape/lipschitz_envelope.h"

namespace offsetopt {

Eigen::VectorXd shrink_outer_limit(const Mesh& mesh, const Eigen::VectorXd& limit,
                                   const std::vector<std::pair<int, int>>& pairs, double factor, double slope) {
  const Eigen::Index n = mesh.V.rows();
  std::vector<char> corner(static_cast<std::size_t>(n), 0);
  for (const auto& [f, g] : pairs)
    for (int face : {f, g})
      if (face >= 0 && face < mesh.F.rows())
        for (int c = 0; c < 3; ++c) corner[static_cast<std::size_t>(mesh.F(face, c))] = 1;
  std::vector<char> shrink = corner;
  for (Eigen::Index face = 0; face < mesh.F.rows(); ++face) {
    bool touches = false;
    for (int c = 0; c < 3; ++c) touches = touches || corner[static_cast<std::size_t>(mesh.F(face, c))];
    if (touches)
      for (int c = 0; c < 3; ++c) shrink[static_cast<std::size_t>(mesh.F(face, c))] = 1;
  }
  Eigen::VectorXd out = limit;
  for (Eigen::Index i = 0; i < n; ++i)
    if (shrink[static_cast<std::size_t>(i)]) out(i) *= factor;
  return lipschitz_envelope(mesh, out, slope);
}

}  // namespace offsetopt
