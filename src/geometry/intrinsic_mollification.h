// Intrinsic mollification of a triangle mesh (Sharp & Crane 2020, "A Laplacian for Nonmanifold
// Triangle Meshes", section 4.5): every edge length is lengthened by the same smallest epsilon
// >= 0 that makes every triangle satisfy the strict triangle inequality with a margin delta,
//   l_j + l_k - l_i >= delta  for every triangle and every corner i,
// and cotangents and areas are then computed from the lengths alone (law of cosines, Heron).
// CAD exports (OpenSCAD STL) carry zero-area triangles with three distinct collinear corners and
// needles with one tiny edge; skeleton contraction collapses triangles on purpose. Mollification
// keeps every cotangent weight and every area finite and positive without dropping or flipping
// a face. It is an intrinsic change only: vertex positions and volume integrals are untouched.
//
// delta = relative_margin * (mean edge length); the project uses relative_margin = 1e-4 (the
// value Sharp & Crane suggest as their default scale). epsilon = max(0, max over triangles and
// corners of delta - (l_j + l_k - l_i)). When epsilon is 0 the caller keeps its extrinsic
// formulas (dot / |cross|), so meshes that need no mollification give bit-identical results.
#pragma once
#include <Eigen/Core>

#include "mesh/mesh.h"

namespace offsetopt {

constexpr double kDefaultMollifyMargin = 1e-4;

struct Mollification {
  double epsilon = 0.0;  // added to every edge length; 0 when no triangle needs it
  double delta = 0.0;    // the margin every triangle keeps after mollification
  long long faces_below_margin = 0;  // triangles that violated the margin before
};

// Edge lengths per face: column k is the length of the edge opposite corner k.
Eigen::Matrix<double, Eigen::Dynamic, 3> face_edge_lengths(const Vertices& V, const Faces& F);

// The epsilon above for lengths from face_edge_lengths. relative_margin 0 disables it.
Mollification intrinsic_mollification(const Eigen::Matrix<double, Eigen::Dynamic, 3>& lengths, double relative_margin);

// Area of a triangle from its edge lengths (Kahan's stable form of Heron's formula; only
// sqrt), 0 when the lengths violate the triangle inequality.
double intrinsic_area(double a, double b, double c);

}  // namespace offsetopt
