// The printable solid from an outer and an inner offset surface with the same connectivity:
// the outer surface plus the inner one with every face reversed (a closed cavity), or, where
// vertices are fixed (both offsets 0: the surfaces coincide there, an opening), the two welded
// along the region into one closed 2-manifold: faces whose three corners are all fixed are
// dropped from both surfaces, the fixed vertices are shared.
#pragma once
#include <vector>

#include "mesh/mesh.h"

namespace offsetopt {

// `outer` and `inner` have identical F; `fixed` has one flag per vertex (may be all zero).
Mesh printable_solid(const Mesh& outer, const Mesh& inner, const std::vector<char>& fixed);

// The outer surface plus every shell of a cavity of its own connectivity (normals out of the
// void), each face reversed: one closed solid with closed cavities.
Mesh hollow_solid(const Mesh& outer, const Mesh& cavity);

}  // namespace offsetopt
