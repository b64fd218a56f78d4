#include "mass/volume_integrals.h"

#include <array>

#include <Eigen/Geometry>

#include "util/neumaier_sum.h"

namespace offsetopt {

Eigen::Vector3d mean_vertex(const Mesh& mesh) {
  if (mesh.V.rows() == 0) return Eigen::Vector3d::Zero();
  std::array<NeumaierSum, 3> sums;
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i)
    for (int c = 0; c < 3; ++c) sums[static_cast<std::size_t>(c)].add(mesh.V(i, c));
  const double n = static_cast<double>(mesh.V.rows());
  return Eigen::Vector3d(sums[0].value() / n, sums[1].value() / n, sums[2].value() / n);
}

VolumeIntegrals volume_integrals(const Mesh& mesh, const Eigen::Vector3d& origin) {
  std::array<NeumaierSum, 10> sums;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)).transpose() - origin;
    const Eigen::Vector3d b = mesh.V.row(mesh.F(f, 1)).transpose() - origin;
    const Eigen::Vector3d c = mesh.V.row(mesh.F(f, 2)).transpose() - origin;
    const double D = a.dot(b.cross(c));
    const Eigen::Vector3d S = a + b + c;
    auto second = [&](int i, int j) { return a(i) * a(j) + b(i) * b(j) + c(i) * c(j) + S(i) * S(j); };
    sums[kIntVolume].add(D / 6.0);
    sums[kIntX].add(D * S.x() / 24.0);
    sums[kIntY].add(D * S.y() / 24.0);
    sums[kIntZ].add(D * S.z() / 24.0);
    sums[kIntXX].add(D * second(0, 0) / 120.0);
    sums[kIntYY].add(D * second(1, 1) / 120.0);
    sums[kIntZZ].add(D * second(2, 2) / 120.0);
    sums[kIntXY].add(D * second(0, 1) / 120.0);
    sums[kIntYZ].add(D * second(1, 2) / 120.0);
    sums[kIntZX].add(D * second(2, 0) / 120.0);
  }
  VolumeIntegrals out;
  out.origin = origin;
  for (int k = 0; k < 10; ++k) out.values(k) = sums[static_cast<std::size_t>(k)].value();
  return out;
}

VolumeIntegrals volume_integrals(const Mesh& mesh) { return volume_integrals(mesh, mean_vertex(mesh)); }

VolumeIntegrals shift_integrals(const VolumeIntegrals& integrals, const Eigen::Vector3d& new_origin) {
  // x' = x + d with d = origin - new_origin:
  // ∫x'_i = ∫x_i + d_i m,  ∫x'_i x'_j = ∫x_i x_j + d_i ∫x_j + d_j ∫x_i + d_i d_j m.
  const Eigen::Vector3d d = integrals.origin - new_origin;
  const Vector10d& v = integrals.values;
  const double m = v(kIntVolume);
  VolumeIntegrals out;
  out.origin = new_origin;
  out.values = v;
  for (int i = 0; i < 3; ++i) out.values(kIntX + i) = v(kIntX + i) + d(i) * m;
  auto second = [&](int slot, int i, int j) {
    out.values(slot) = v(slot) + d(i) * v(kIntX + j) + d(j) * v(kIntX + i) + d(i) * d(j) * m;
  };
  second(kIntXX, 0, 0);
  second(kIntYY, 1, 1);
  second(kIntZZ, 2, 2);
  second(kIntXY, 0, 1);
  second(kIntYZ, 1, 2);
  second(kIntZX, 2, 0);
  return out;
}

VolumeIntegrals add(const VolumeIntegrals& a, const VolumeIntegrals& b) {
  VolumeIntegrals out = a;
  out.values += (b.origin == a.origin ? b : shift_integrals(b, a.origin)).values;
  return out;
}

VolumeIntegrals subtract(const VolumeIntegrals& a, const VolumeIntegrals& b) {
  VolumeIntegrals out = a;
  out.values -= (b.origin == a.origin ? b : shift_integrals(b, a.origin)).values;
  return out;
}

}  // namespace offsetopt
