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
