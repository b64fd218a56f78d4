#include "mass/mass_properties.h"

#include <cmath>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

namespace offsetopt {

Vector10d mass_properties(const VolumeIntegrals& integrals) {
  const Vector10d& f = integrals.values;
  const double m = f(kIntVolume);
  const Eigen::Vector3d c_local(f(kIntX) / m, f(kIntY) / m, f(kIntZ) / m);
  // Central second moments S_ij = ∫(x_i − c_i)(x_j − c_j) = ∫x_i x_j − m c_i c_j in the local frame.
  const double Sxx = f(kIntXX) - m * c_local.x() * c_local.x();
  const double Syy = f(kIntYY) - m * c_local.y() * c_local.y();
  const double Szz = f(kIntZZ) - m * c_local.z() * c_local.z();
  const double Sxy = f(kIntXY) - m * c_local.x() * c_local.y();
  const double Syz = f(kIntYZ) - m * c_local.y() * c_local.z();
  const double Szx = f(kIntZX) - m * c_local.z() * c_local.x();
  Vector10d P;
  P(kMass) = m;
  P(kCx) = integrals.origin.x() + c_local.x();
  P(kCy) = integrals.origin.y() + c_local.y();
  P(kCz) = integrals.origin.z() + c_local.z();
  P(kIxx) = Syy + Szz;
  P(kIyy) = Sxx + Szz;
  P(kIzz) = Sxx + Syy;
  P(kIxy) = -Sxy;
  P(kIyz) = -Syz;
  P(kIzx) = -Szx;
  return P;
}

Vector10d mass_properties(const Mesh& mesh) { return mass_properties(volume_integrals(mesh)); }

Eigen::Matrix<double, 10, 10> mass_properties_jacobian_wrt_integrals(const VolumeIntegrals& integrals) {
  const Vector10d& f = integrals.values;
  const double m = f(kIntVolume);
  const double c[3] = {f(kIntX) / m, f(kIntY) / m, f(kIntZ) / m};
  Eigen::Matrix<double, 10, 10> J = Eigen::Matrix<double, 10, 10>::Zero();
  J(kMass, kIntVolume) = 1.0;
  for (int i = 0; i < 3; ++i) {
    J(kCx + i, kIntX + i) = 1.0 / m;         // c_i = o_i + f_i / m
    J(kCx + i, kIntVolume) = -c[i] / m;
  }
  // dS_ij: ∂/∂f_ij = 1, ∂/∂f_i = −c_j, ∂/∂f_j = −c_i, ∂/∂m = c_i c_j (for i = j: −2c_i and c_i²).
  auto central = [&](int i, int j, int slot) {
    Eigen::Matrix<double, 1, 10> row = Eigen::Matrix<double, 1, 10>::Zero();
    row(slot) = 1.0;
    row(kIntX + i) -= c[j];
    row(kIntX + j) -= c[i];
    row(kIntVolume) = c[i] * c[j];
    return row;
  };
  const auto Sxx = central(0, 0, kIntXX), Syy = central(1, 1, kIntYY), Szz = central(2, 2, kIntZZ);
  J.row(kIxx) = Syy + Szz;
  J.row(kIyy) = Sxx + Szz;
  J.row(kIzz) = Sxx + Syy;
  J.row(kIxy) = -central(0, 1, kIntXY);
  J.row(kIyz) = -central(1, 2, kIntYZ);
  J.row(kIzx) = -central(2, 0, kIntZX);
  return J;
}

Eigen::Matrix3d inertia_tensor(const Vector10d& P) {
  Eigen::Matrix3d I;
  I << P(kIxx), P(kIxy), P(kIzx),
       P(kIxy), P(kIyy), P(kIyz),
       P(kIzx), P(kIyz), P(kIzz);
  return I;
}

PrincipalInertia principal_inertia(const Vector10d& P) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(inertia_tensor(P));
  PrincipalInertia out;
  out.moments = solver.eigenvalues();
  out.axes = solver.eigenvectors();
  for (int k = 0; k < 2; ++k) {
    int largest = 0;
    for (int i = 1; i < 3; ++i)
      if (std::fabs(out.axes(i, k)) > std::fabs(out.axes(largest, k))) largest = i;
    if (out.axes(largest, k) < 0.0) out.axes.col(k) = -out.axes.col(k);
  }
  out.axes.col(2) = out.axes.col(0).cross(out.axes.col(1));
  out.axes = (out.axes.array() + 0.0).matrix();  // -0 -> +0, so reports never print "-0"
  return out;
}

}  // namespace offsetopt
