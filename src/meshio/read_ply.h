// PLY reader: ASCII, binary little-endian and binary big-endian.
//
// Only the vertex positions (properties x, y, z of element `vertex`, any scalar type) and the
// face lists (list property `vertex_indices` or `vertex_index` of element `face`, any integer
// count and index type: uchar, ushort, uint, int, ...) are used; every other element and
// property is skipped according to its declared type. Header lines may end in CRLF (the binary
// data then starts after "end_header\r\n"). Every element count is checked against the bytes
// left after the header at the element's smallest encoding (binary: the sum of its scalar sizes
// and list-count sizes; ASCII: two characters per property) before anything is allocated, and
// every list count against the bytes still left. Polygons are fan-triangulated.
#pragma once
#include <string>

#include "meshio/read_raw_mesh.h"

namespace offsetopt {

RawMesh read_ply(const std::string& name, const std::string& bytes);

}  // namespace offsetopt
