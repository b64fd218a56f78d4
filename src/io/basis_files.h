// File formats of `offsetopt basis` outputs, as bytes (the caller writes them):
//  - eigenvectors_npy: NumPy .npy version 1.0, little-endian float64 ('<f8'), C order, shape
//    (#V, k): column j is eigenvector j. numpy.load reads it directly.
//  - eigenvectors_csv: a header line "phi_0,...,phi_{k-1}", then #V lines of k numbers in
//    shortest round-trip form (reads back to the same doubles).
//  - matrix_market: a symmetric sparse matrix as Matrix Market "coordinate real symmetric", the
//    lower triangle, 1-based indices, shortest round-trip values (scipy.io.mmread reads it).
//  - scalar_ply: binary little-endian PLY of the mesh with one per-vertex scalar as the property
//    "quality" (MeshLab shows it) plus red/green/blue from a blue-white-red map symmetric about 0
//    (any viewer shows it). Coordinates as float32: the file is for looking at, not for computing.
#pragma once
#include <Eigen/Sparse>
#include <string>

#include "mesh/mesh.h"

namespace offsetopt {

std::string eigenvectors_npy(const Eigen::MatrixXd& vectors);
std::string eigenvectors_csv(const Eigen::MatrixXd& vectors);
std::string matrix_market(const Eigen::SparseMatrix<double>& symmetric);
std::string scalar_ply(const Mesh& mesh, const Eigen::VectorXd& values);

}  // namespace offsetopt
