// A coarse copy of a large mesh and the map back to it (issue 22: scans of 10^6 vertices). The
// stages whose result is a low-frequency object, the meso-skeleton (skeleton/laplacian_contraction.h)
// and the manifold-harmonic basis, are computed on the copy and carried back to every input
// vertex: a vertex the decimation kept (skeleton/decimate_mesh.h) takes its coarse value, any
// other the barycentric combination at the closest point of the coarse surface.
#pragma once
#include <array>
#include <vector>

#include <Eigen/Core>

#include "mesh/mesh.h"
#include "skeleton/decimate_mesh.h"

namespace offsetopt {

struct CoarseCopy {
  DecimatedMesh decimated;
  // Per input vertex: three coarse vertices and their weights (summing to 1; a kept vertex has
  // weights 1, 0, 0 on itself).
  std::vector<std::array<int, 3>> corners;
  std::vector<std::array<double, 3>> weights;
};

// Decimates to `target_vertices` and finds every input vertex's closest coarse point. The
// vertices are split in fixed ranges over `threads` threads; the result is the same for any count.
CoarseCopy coarse_copy(const Vertices& V, const Faces& F, int target_vertices, int threads);

// Values on the coarse vertices (#coarse by any) carried to the input vertices (#input by the same).
Eigen::MatrixXd carry_to_input(const CoarseCopy& copy, const Eigen::MatrixXd& coarse_values);

}  // namespace offsetopt
