// Small, independent helpers shared by the tests of src/mass: rotations from det_math, mesh
// transforms, the closed-and-oriented check (tests/mesh_checks.h), and central finite differences.
#pragma once
#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "../mesh_checks.h"
#include "mesh/mesh.h"
#include "util/det_math.h"
#include "util/rng.h"

namespace offsetopt::test {

inline Eigen::Matrix3d rotation_from_angles(double a, double b, double c) {
  double sa, ca, sb, cb, sc, cc;
  det_sincos(a, sa, ca);
  det_sincos(b, sb, cb);
  det_sincos(c, sc, cc);
  Eigen::Matrix3d rz, ry, rx;
  rz << ca, -sa, 0, sa, ca, 0, 0, 0, 1;
  ry << cb, 0, sb, 0, 1, 0, -sb, 0, cb;
  rx << 1, 0, 0, 0, cc, -sc, 0, sc, cc;
  return rz * ry * rx;
}

inline Eigen::Matrix3d random_rotation(Rng& rng) {
  return rotation_from_angles(rng.uniform(-kPi, kPi), rng.uniform(-kPi, kPi), rng.uniform(-kPi, kPi));
}

// x -> R x + t for every vertex.
inline Mesh transformed(const Mesh& mesh, const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  Mesh out = mesh;
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) out.V.row(i) = (R * mesh.V.row(i).transpose() + t).transpose();
  return out;
}

inline double bbox_diagonal(const Mesh& mesh) { return (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).norm(); }

// Each vertex moved by a uniform random vector of at most `amount` per coordinate.
inline Mesh perturbed(const Mesh& mesh, double amount, Rng& rng) {
  Mesh out = mesh;
  for (Eigen::Index i = 0; i < out.V.rows(); ++i)
    for (int c = 0; c < 3; ++c) out.V(i, c) += rng.uniform(-amount, amount);
  return out;
}

// Central difference of a vector-valued function of the mesh with respect to V(vertex, coord).
template <class Function>
auto central_difference(Mesh mesh, Eigen::Index vertex, int coord, double h, const Function& f) {
  const double x = mesh.V(vertex, coord);
  mesh.V(vertex, coord) = x + h;
  const auto plus = f(mesh);
  mesh.V(vertex, coord) = x - h;
  const auto minus = f(mesh);
  return ((plus - minus) / (2.0 * h)).eval();
}

}  // namespace offsetopt::test
