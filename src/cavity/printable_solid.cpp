#include "cavity/printable_solid.h"

namespace offsetopt {

Mesh printable_solid(const Mesh& outer, const Mesh& inner, const std::vector<char>& fixed) {
  const Eigen::Index n = outer.V.rows();
  // Inner vertex i becomes vertex inner_index[i]: the outer vertex itself where fixed.
  std::vector<int> inner_index(static_cast<std::size_t>(n));
  int next = static_cast<int>(n);
  for (Eigen::Index i = 0; i < n; ++i) inner_index[static_cast<std::size_t>(i)] = fixed[static_cast<std::size_t>(i)] ? static_cast<int>(i) : next++;
  auto all_fixed = [&](const Mesh& m, Eigen::Index f) {
    return fixed[static_cast<std::size_t>(m.F(f, 0))] && fixed[static_cast<std::size_t>(m.F(f, 1))] &&
           fixed[static_cast<std::size_t>(m.F(f, 2))];
  };
  Eigen::Index kept = 0;
  for (Eigen::Index f = 0; f < outer.F.rows(); ++f) kept += all_fixed(outer, f) ? 0 : 1;

  Mesh solid;
  solid.V.resize(next, 3);
  solid.V.topRows(n) = outer.V;
  for (Eigen::Index i = 0; i < n; ++i)
    if (!fixed[static_cast<std::size_t>(i)]) solid.V.row(inner_index[static_cast<std::size_t>(i)]) = inner.V.row(i);
  solid.F.resize(2 * kept, 3);
  Eigen::Index row = 0;
  for (Eigen::Index f = 0; f < outer.F.rows(); ++f)
    if (!all_fixed(outer, f)) solid.F.row(row++) = outer.F.row(f);
  for (Eigen::Index f = 0; f < inner.F.rows(); ++f) {
    if (all_fixed(inner, f)) continue;
    // Reversed: the cavity's faces point into the void, i.e. out of the material.
    solid.F(row, 0) = inner_index[static_cast<std::size_t>(inner.F(f, 0))];
    solid.F(row, 1) = inner_index[static_cast<std::size_t>(inner.F(f, 2))];
    solid.F(row, 2) = inner_index[static_cast<std::size_t>(inner.F(f, 1))];
    ++row;
  }
  return solid;
}

Mesh hollow_solid(const Mesh& outer, const Mesh& cavity) {
  Mesh solid;
  const Eigen::Index n = outer.V.rows();
  solid.V.resize(n + cavity.V.rows(), 3);
  solid.V.topRows(n) = outer.V;
  solid.V.bottomRows(cavity.V.rows()) = cavity.V;
  solid.F.resize(outer.F.rows() + cavity.F.rows(), 3);
  solid.F.topRows(outer.F.rows()) = outer.F;
  for (Eigen::Index f = 0; f < cavity.F.rows(); ++f) {
    const Eigen::Index row = outer.F.rows() + f;
    solid.F(row, 0) = static_cast<int>(n) + cavity.F(f, 0);
    solid.F(row, 1) = static_cast<int>(n) + cavity.F(f, 2);
    solid.F(row, 2) = static_cast<int>(n) + cavity.F(f, 1);
  }
  return solid;
}

}  // namespace offsetopt
