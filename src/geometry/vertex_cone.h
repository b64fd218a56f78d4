// Does a direction leave a surface vertex into the solid? At a vertex the solid occupies a cone
// bounded by the fan of incident faces; the vertex normal alone does not decide it (a direction
// with d . n < 0 can still leave through a neighbouring face at a sharp convex corner, and one
// with d . n > 0 can enter at a saddle). The test evaluates the generalised winding number of the
// fan alone at x + eps d (eps = 1e-4 times the shortest incident edge): near the apex the fan
// looks like its infinite cone, whose winding number is 1 - Omega/(4 pi) > 0 inside and
// -Omega/(4 pi) < 0 outside (Omega the cone's interior solid angle), so the sign decides.
// Solid angles by Van Oosterom & Strackee with det_atan2 (deterministic).
#pragma once
#include <Eigen/Core>
#include <vector>

#include "mesh/mesh.h"

namespace offsetopt {

// `fan` lists the faces incident to `vertex`; `direction` need not be unit (it must be nonzero).
bool direction_enters_solid(const Vertices& V, const Faces& F, const std::vector<int>& fan, int vertex,
                            const Eigen::Vector3d& direction);

// Faces incident to each vertex, in increasing face order: CSR arrays (offsets has #V + 1 entries).
struct VertexFaces {
  std::vector<int> offsets;
  std::vector<int> faces;
  std::vector<int> of(int vertex) const {
    return std::vector<int>(faces.begin() + offsets[static_cast<std::size_t>(vertex)],
                            faces.begin() + offsets[static_cast<std::size_t>(vertex) + 1]);
  }
};
VertexFaces vertex_faces(Eigen::Index vertex_count, const Faces& F);

}  // namespace offsetopt
