// The ten raw volume integrals of the solid bounded by a closed, outward-oriented triangle mesh,
// exact for the polyhedron (divergence theorem; Mirtich 1996, "Fast and Accurate Computation of
// Polyhedral Mass Properties"; Eberly, "Polyhedral Mass Properties (Revisited)"; Messner and
// Taylor 1980). They are the raw material of the 10 mass properties of the paper's eq. 4.
//
// Each triangle (a, b, c) contributes the signed tetrahedron (o, a, b, c) spanned with the frame
// origin o; with a, b, c measured from o, D = a·(b×c) (six times its signed volume), S = a+b+c:
//   ∫1 = D/6,   ∫x_i = D S_i / 24,   ∫x_i x_j = D (Σ_corners v_i v_j + S_i S_j) / 120.
// Measuring from an origin near the solid (the mean vertex by default) keeps every term small, so
// a mesh 1e6 away from the world origin loses no digits; the ten sums are compensated (Neumaier)
// and run over the faces in index order, so the result is deterministic.
#pragma once
#include <Eigen/Core>

#include "mesh/mesh.h"

namespace offsetopt {

using Vector10d = Eigen::Matrix<double, 10, 1>;

// Index of each raw integral in VolumeIntegrals::values (coordinates measured from `origin`).
enum RawIntegral : int {
  kIntVolume = 0,  // ∫1
  kIntX = 1,       // ∫x
  kIntY = 2,       // ∫y
  kIntZ = 3,       // ∫z
  kIntXX = 4,      // ∫x²
  kIntYY = 5,      // ∫y²
  kIntZZ = 6,      // ∫z²
  kIntXY = 7,      // ∫xy
  kIntYZ = 8,      // ∫yz
  kIntZX = 9,      // ∫zx
};

struct VolumeIntegrals {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // the integrands' coordinates are x - origin
  Vector10d values = Vector10d::Zero();              // ordered as RawIntegral
};

// The mean of the vertices (compensated sum): the default reference point.
Eigen::Vector3d mean_vertex(const Mesh& mesh);

// Integrals with coordinates measured from `origin`. The mesh must be closed and outward
// oriented; for an open or inside-out mesh the numbers are well defined but meaningless
// (negative volume when inside out).
VolumeIntegrals volume_integrals(const Mesh& mesh, const Eigen::Vector3d& origin);

// Same, measured from mean_vertex(mesh).
VolumeIntegrals volume_integrals(const Mesh& mesh);

// The same integrals measured from `new_origin` (parallel-axis terms; exact up to rounding).
VolumeIntegrals shift_integrals(const VolumeIntegrals& integrals, const Eigen::Vector3d& new_origin);

// Integrals are additive over disjoint solids. The result is in a's frame (b is shifted first).
// A shell between an outer surface and an inner surface inside it: subtract(outer, inner).
VolumeIntegrals add(const VolumeIntegrals& a, const VolumeIntegrals& b);
VolumeIntegrals subtract(const VolumeIntegrals& a, const VolumeIntegrals& b);

}  // namespace offsetopt
