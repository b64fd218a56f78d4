// src/mass (this is the folder's main header): the physics of a solid at density 1. It owns the
// volume integrals and their vertex gradients, the 10 mass properties (this header) and their
// gradient, surface area, static stability on the ground (stability.h), the stable pose on a
// convex-hull facet (stable_pose.h) and buoyancy. Layer: above geometry, meshio and io; it may
// include util, optim, mesh, geometry, meshio, io and itself, not sparse, spectral or skeleton
// (it solves no linear systems), nor shape or cli.
//
// The 10 mass properties of the paper's eq. 4 (Musialski et al. 2015),
//   P = [m, cx, cy, cz, Ixx, Iyy, Izz, Ixy, Iyz, Izx],
// at density 1 (m is the volume), from the raw volume integrals (mass/volume_integrals.h).
// The inertia tensor is taken about the centre of mass, I = ∫(|r|²E − r rᵀ)dV with r = x − c, so
// the diagonal is positive (Ixx = ∫(y² + z²)dV) and the products carry the minus sign
// (Ixy = −∫(x−cx)(y−cy)dV): I is the matrix [[Ixx, Ixy, Izx], [Ixy, Iyy, Iyz], [Izx, Iyz, Izz]].
// Everything is evaluated in the integrals' own frame (small numbers near the solid) and only
// the centre of mass is translated back, so no precision is lost far from the world origin.
#pragma once
#include <Eigen/Core>

#include "mass/volume_integrals.h"

namespace offsetopt {

enum MassProperty : int {
  kMass = 0,
  kCx = 1,
  kCy = 2,
  kCz = 3,
  kIxx = 4,
  kIyy = 5,
  kIzz = 6,
  kIxy = 7,
  kIyz = 8,
  kIzx = 9,
};

// P from the integrals. The volume must be nonzero (the centre of mass divides by it).
Vector10d mass_properties(const VolumeIntegrals& integrals);

// Shorthand: mass_properties(volume_integrals(mesh)).
Vector10d mass_properties(const Mesh& mesh);

// The 10 by 10 derivative ∂P/∂values of mass_properties with respect to integrals.values
// (row: property as MassProperty, column: integral as RawIntegral), for the chain rule
// dF/dX = (∂F/∂P)(∂P/∂values)(∂values/∂X).
Eigen::Matrix<double, 10, 10> mass_properties_jacobian_wrt_integrals(const VolumeIntegrals& integrals);

// The symmetric 3 by 3 inertia tensor I (about the centre of mass) held in P.
Eigen::Matrix3d inertia_tensor(const Vector10d& P);

struct PrincipalInertia {
  Eigen::Vector3d moments;  // eigenvalues of I, ascending
  // Column k is the unit axis of moments(k). Sign convention: columns 0 and 1 have their
  // largest-magnitude component positive (the first such component on a tie), column 2 is
  // column 0 × column 1, so the frame is right-handed. Axes of repeated moments are any
  // orthonormal basis of their eigenspace.
  Eigen::Matrix3d axes;
};

// Eigen-decomposition of the inertia tensor (Eigen's iterative SelfAdjointEigenSolver: only
// arithmetic and sqrt, so deterministic).
PrincipalInertia principal_inertia(const Vector10d& P);

}  // namespace offsetopt
