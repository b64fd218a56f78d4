// Outward unit vertex normals of a closed, counter-clockwise-oriented mesh: the sum of the
// incident faces' (b - a) x (c - a) (area weighting), normalised. #V by 3. A vertex whose sum
// vanishes (isolated, or faces cancelling) gets the zero vector; callers treat it as unusable.
#pragma once
#include "mesh/mesh.h"

namespace offsetopt {

Vertices vertex_normals(const Vertices& V, const Faces& F);

}  // namespace offsetopt
