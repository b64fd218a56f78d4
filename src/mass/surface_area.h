// Total area of a triangle mesh: Σ |(b − a) × (c − a)| / 2 over the faces in index order,
// compensated (Neumaier), edges measured from each triangle's first corner.
#pragma once
#include "mesh/mesh.h"

namespace offsetopt {

double surface_area(const Mesh& mesh);

}  // namespace offsetopt
