// The connected shells of a triangle mesh (faces joined through shared vertices) and the signed
// volume each encloses (divergence theorem: the sum of the tetrahedra each face spans with
// `origin`, in face order), positive for a shell whose faces point out of it, negative for a
// cavity written reversed. Shells are numbered in the order of their lowest face.
#pragma once
#include <vector>

#include <Eigen/Core>

#include "mesh/mesh.h"

namespace offsetopt {

struct MeshShellsOptions {
  // Each shell's tetrahedra summed with Neumaier's compensation, six times the volume divided
  // once at the end (validation: the sign of a nearly flat shell decides a defect), instead of
  // a plain running sum of each tetrahedron's volume (the contour and the picture, whose
  // recorded outputs were made with it).
  bool compensated = false;
};

struct MeshShells {
  int count = 0;
  std::vector<int> shell_of_face;  // #F
  std::vector<double> volume;      // per shell; measure from a point near the mesh for accuracy
  double total_volume = 0.0;       // the shells' volumes summed in shell order (compensated too)
};

MeshShells mesh_shells(const Mesh& mesh, const Eigen::Vector3d& origin, const MeshShellsOptions& options = {});

}  // namespace offsetopt
