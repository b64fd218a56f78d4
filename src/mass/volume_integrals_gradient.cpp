#include "mass/volume_integrals_gradient.h"

#include <array>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "util/neumaier_pair.h"
#include "util/neumaier_sum.h"

namespace offsetopt {

void accumulate_volume_integrals_gradient(const Mesh& mesh, const Eigen::Vector3d& origin, const Vector10d& w,
                                          Vertices& gradient) {
  // W u/120 with W = [[2wxx, wxy, wzx], [wxy, 2wyy, wyz], [wzx, wyz, 2wzz]] collects the
  // derivative of Σ_ij w_ij G_ij with respect to one corner (G_ij's derivative is e_i u_j + e_j u_i).
  Eigen::Matrix3d W;
  W << 2.0 * w(kIntXX), w(kIntXY), w(kIntZX),
       w(kIntXY), 2.0 * w(kIntYY), w(kIntYZ),
       w(kIntZX), w(kIntYZ), 2.0 * w(kIntZZ);
  const Eigen::Vector3d w_linear(w(kIntX), w(kIntY), w(kIntZ));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const int ia = mesh.F(f, 0), ib = mesh.F(f, 1), ic = mesh.F(f, 2);
    const Eigen::Vector3d a = mesh.V.row(ia).transpose() - origin;
    const Eigen::Vector3d b = mesh.V.row(ib).transpose() - origin;
    const Eigen::Vector3d c = mesh.V.row(ic).transpose() - origin;
    const Eigen::Vector3d bc = b.cross(c), ca = c.cross(a), ab = a.cross(b);
    const double D = a.dot(bc);
    const Eigen::Vector3d S = a + b + c;
    auto G = [&](int i, int j) { return a(i) * a(j) + b(i) * b(j) + c(i) * c(j) + S(i) * S(j); };
    // The weighted sum of the triangle's ten terms divided by D: the factor of ∂D.
    const double per_D = w(kIntVolume) / 6.0 + w_linear.dot(S) / 24.0 +
                         (w(kIntXX) * G(0, 0) + w(kIntYY) * G(1, 1) + w(kIntZZ) * G(2, 2) + w(kIntXY) * G(0, 1) +
                          w(kIntYZ) * G(1, 2) + w(kIntZX) * G(2, 0)) / 120.0;
    const Eigen::Vector3d linear_part = w_linear / 24.0;
    const Eigen::Vector3d ga = bc * per_D + D * (linear_part + W * (a + S) / 120.0);
    const Eigen::Vector3d gb = ca * per_D + D * (linear_part + W * (b + S) / 120.0);
    const Eigen::Vector3d gc = ab * per_D + D * (linear_part + W * (c + S) / 120.0);
    gradient.row(ia) += ga.transpose();
    gradient.row(ib) += gb.transpose();
    gradient.row(ic) += gc.transpose();
  }
}

Eigen::MatrixXd volume_integrals_jacobian(const Mesh& mesh, const Eigen::Vector3d& origin) {
  const Eigen::Index n = mesh.V.rows();
  Eigen::MatrixXd J(10, 3 * n);
  for (int k = 0; k < 10; ++k) {
    Vertices g = Vertices::Zero(n, 3);
    accumulate_volume_integrals_gradient(mesh, origin, Vector10d::Unit(k), g);
    for (Eigen::Index i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) J(k, 3 * i + c) = g(i, c);
  }
  return J;
}

Eigen::Matrix<double, 10, Eigen::Dynamic> volume_integrals_directional_jacobian(const Mesh& mesh,
                                                                                const Eigen::Vector3d& origin,
                                                                                const Vertices& directions) {
  Eigen::Matrix<double, 10, Eigen::Dynamic> J = Eigen::Matrix<double, 10, Eigen::Dynamic>::Zero(10, mesh.V.rows());
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const int corner_index[3] = {mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2)};
    const Eigen::Vector3d p[3] = {mesh.V.row(corner_index[0]).transpose() - origin,
                                  mesh.V.row(corner_index[1]).transpose() - origin,
                                  mesh.V.row(corner_index[2]).transpose() - origin};
    const double D = p[0].dot(p[1].cross(p[2]));
    const Eigen::Vector3d S = p[0] + p[1] + p[2];
    auto G = [&](int i, int j) { return p[0](i) * p[0](j) + p[1](i) * p[1](j) + p[2](i) * p[2](j) + S(i) * S(j); };
    const double Gxx = G(0, 0), Gyy = G(1, 1), Gzz = G(2, 2), Gxy = G(0, 1), Gyz = G(1, 2), Gzx = G(2, 0);
    for (int corner = 0; corner < 3; ++corner) {
      const Eigen::Vector3d d = directions.row(corner_index[corner]).transpose();
      // ∂D/∂(this corner) is the cross product of the other two, in cyclic order.
      const double dD = p[(corner + 1) % 3].cross(p[(corner + 2) % 3]).dot(d);
      const Eigen::Vector3d u = p[corner] + S;  // ∂G_ij/∂corner = e_i u_j + e_j u_i
      auto column = J.col(corner_index[corner]);
      column(kIntVolume) += dD / 6.0;
      column(kIntX) += (dD * S.x() + D * d.x()) / 24.0;
      column(kIntY) += (dD * S.y() + D * d.y()) / 24.0;
      column(kIntZ) += (dD * S.z() + D * d.z()) / 24.0;
      column(kIntXX) += (dD * Gxx + D * 2.0 * d.x() * u.x()) / 120.0;
      column(kIntYY) += (dD * Gyy + D * 2.0 * d.y() * u.y()) / 120.0;
      column(kIntZZ) += (dD * Gzz + D * 2.0 * d.z() * u.z()) / 120.0;
      column(kIntXY) += (dD * Gxy + D * (d.x() * u.y() + d.y() * u.x())) / 120.0;
      column(kIntYZ) += (dD * Gyz + D * (d.y() * u.z() + d.z() * u.y())) / 120.0;
      column(kIntZX) += (dD * Gzx + D * (d.z() * u.x() + d.x() * u.z())) / 120.0;
    }
  }
  return J;
}

namespace {

// The fused pass for a Jacobian of Rows rows (1, 4 or 10) and the first Sums integrals (Rows to
// 10), so the loop carries no row tests. Shifted = false: the origin is +0, whose subtraction
// changes no coordinate's bits (x − (+0) == x, also for x = −0), so it is skipped.
template <int Rows, int Sums, bool Shifted>
void integrals_and_jacobian_rows(const Vertices& V, const Faces& F, const Eigen::Vector3d& origin,
                                 const Vertices& directions, Vector10d& integrals, Eigen::MatrixXd& jacobian,
                                 bool jacobian_is_zero) {
  static_assert(Rows <= Sums, "every integral with a Jacobian row is summed");
  constexpr bool first_moments = Rows >= 4, second_moments = Rows >= 10;
  constexpr bool second_moment_sums = Sums >= 10;
  if (!jacobian_is_zero) jacobian.setZero(Rows, V.rows());
  NeumaierSum volume_sum;                          // Sums = 1
  std::array<NeumaierPair, (Sums + 1) / 2> sums;   // Sums = 4 or 10: integrals 2j and 2j + 1
  auto position = [&](int index) -> Eigen::Vector3d {
    if constexpr (Shifted) return V.row(index).transpose() - origin;
    return V.row(index).transpose();
  };
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const int corner_index[3] = {F(f, 0), F(f, 1), F(f, 2)};
    const Eigen::Vector3d p[3] = {position(corner_index[0]), position(corner_index[1]), position(corner_index[2])};
    const double D = p[0].dot(p[1].cross(p[2]));
    const Eigen::Vector3d S = p[0] + p[1] + p[2];
    auto G = [&](int i, int j) { return p[0](i) * p[0](j) + p[1](i) * p[1](j) + p[2](i) * p[2](j) + S(i) * S(j); };
    double Gxx = 0.0, Gyy = 0.0, Gzz = 0.0, Gxy = 0.0, Gyz = 0.0, Gzx = 0.0;
    if constexpr (second_moment_sums) {
      Gxx = G(0, 0), Gyy = G(1, 1), Gzz = G(2, 2), Gxy = G(0, 1), Gyz = G(1, 2), Gzx = G(2, 0);
    }
    // The same terms, in the same order, as volume_integrals(); sums in pairs (kInt order).
    if constexpr (Sums == 1) {
      volume_sum.add(D / 6.0);
    } else {
      sums[0].add(D / 6.0, D * S.x() / 24.0);
      sums[1].add(D * S.y() / 24.0, D * S.z() / 24.0);
    }
    if constexpr (second_moment_sums) {
      sums[2].add(D * Gxx / 120.0, D * Gyy / 120.0);
      sums[3].add(D * Gzz / 120.0, D * Gxy / 120.0);
      sums[4].add(D * Gyz / 120.0, D * Gzx / 120.0);
    }
    for (int corner = 0; corner < 3; ++corner) {
      const Eigen::Vector3d d = directions.row(corner_index[corner]).transpose();
      const double dD = p[(corner + 1) % 3].cross(p[(corner + 2) % 3]).dot(d);
      double* column = jacobian.col(corner_index[corner]).data();
      column[kIntVolume] += dD / 6.0;
      if constexpr (!first_moments) continue;
      column[kIntX] += (dD * S.x() + D * d.x()) / 24.0;
      column[kIntY] += (dD * S.y() + D * d.y()) / 24.0;
      column[kIntZ] += (dD * S.z() + D * d.z()) / 24.0;
      if constexpr (!second_moments) continue;
      const Eigen::Vector3d u = p[corner] + S;
      column[kIntXX] += (dD * Gxx + D * 2.0 * d.x() * u.x()) / 120.0;
      column[kIntYY] += (dD * Gyy + D * 2.0 * d.y() * u.y()) / 120.0;
      column[kIntZZ] += (dD * Gzz + D * 2.0 * d.z() * u.z()) / 120.0;
      column[kIntXY] += (dD * Gxy + D * (d.x() * u.y() + d.y() * u.x())) / 120.0;
      column[kIntYZ] += (dD * Gyz + D * (d.y() * u.z() + d.z() * u.y())) / 120.0;
      column[kIntZX] += (dD * Gzx + D * (d.z() * u.x() + d.x() * u.z())) / 120.0;
    }
  }
  integrals.setConstant(std::numeric_limits<double>::quiet_NaN());
  if constexpr (Sums == 1) {
    integrals(kIntVolume) = volume_sum.value();
  } else {
    for (int k = 0; k < Sums; ++k) integrals(k) = sums[static_cast<std::size_t>(k / 2)].value(k % 2);
  }
}

template <int Rows, int Sums>
void integrals_and_jacobian_from(const Vertices& V, const Faces& F, const Eigen::Vector3d& origin,
                                 const Vertices& directions, Vector10d& integrals, Eigen::MatrixXd& jacobian,
                                 bool jacobian_is_zero) {
  bool positive_zero = true;
  for (int k = 0; k < 3; ++k) positive_zero = positive_zero && origin(k) == 0.0 && !std::signbit(origin(k));
  if (positive_zero)
    integrals_and_jacobian_rows<Rows, Sums, false>(V, F, origin, directions, integrals, jacobian, jacobian_is_zero);
  else
    integrals_and_jacobian_rows<Rows, Sums, true>(V, F, origin, directions, integrals, jacobian, jacobian_is_zero);
}

}  // namespace

void volume_integrals_and_directional_jacobian(const Vertices& V, const Faces& F, const Eigen::Vector3d& origin,
                                               const Vertices& directions, Vector10d& integrals,
                                               Eigen::MatrixXd& jacobian, int jacobian_rows, int integral_count,
                                               bool jacobian_is_zero) {
  const Eigen::Index rows = jacobian_rows >= 10 ? 10 : (jacobian_rows >= 4 ? 4 : 1);
  jacobian_is_zero = jacobian_is_zero && jacobian.rows() == rows && jacobian.cols() == V.rows();
  const bool all = integral_count >= 10;
  if (jacobian_rows >= 10)
    integrals_and_jacobian_from<10, 10>(V, F, origin, directions, integrals, jacobian, jacobian_is_zero);
  else if (jacobian_rows >= 4)
    (all ? integrals_and_jacobian_from<4, 10> : integrals_and_jacobian_from<4, 4>)(V, F, origin, directions, integrals,
                                                                                    jacobian, jacobian_is_zero);
  else if (all)
    integrals_and_jacobian_from<1, 10>(V, F, origin, directions, integrals, jacobian, jacobian_is_zero);
  else if (integral_count >= 4)
    integrals_and_jacobian_from<1, 4>(V, F, origin, directions, integrals, jacobian, jacobian_is_zero);
  else
    integrals_and_jacobian_from<1, 1>(V, F, origin, directions, integrals, jacobian, jacobian_is_zero);
}

}  // namespace offsetopt
