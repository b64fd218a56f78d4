// src/mesh: the triangle mesh type (this header) and what constructs meshes in memory: the
// primitives (primitives.h) and the demo meshes built from them (demo_meshes.h). Reading,
// writing and validating mesh files is src/meshio. Layer: above util and optim, below geometry;
// it may include only util/ and optim/ (and Eigen).
//
// The triangle mesh every stage passes around, libigl style: V is #V by 3 (x, y, z per row),
// F is #F by 3 (vertex indices per row, counter-clockwise seen from outside, so the
// right-hand normal points out of the solid).
#pragma once
#include <Eigen/Core>

namespace offsetopt {

using Vertices = Eigen::Matrix<double, Eigen::Dynamic, 3>;
using Faces = Eigen::Matrix<int, Eigen::Dynamic, 3>;

struct Mesh {
  Vertices V;
  Faces F;
  Eigen::Index vertex_count() const { return V.rows(); }
  Eigen::Index face_count() const { return F.rows(); }
};

}  // namespace offsetopt
