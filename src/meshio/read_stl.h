// STL reader, ASCII and binary.
//
// Binary versus ASCII is decided by size arithmetic, not by the word `solid` (binary files whose
// 80-byte header starts with "solid" are common): a file whose size is exactly
// 84 + 50 * count (computed in 64 bits; a count of 2^31 + 1 wraps in 32) is binary. Otherwise a
// file starting with "solid" and free of NUL bytes is parsed as ASCII; a larger file is binary
// with the bytes after the last triangle ignored (a warning); a smaller one is truncated.
//
// STL stores every triangle's corners separately. Corners at exactly the same position
// (float32 values compared as numbers, so -0 == +0) are welded into one vertex; vertices are
// numbered in order of first appearance. Non-finite corners are welded only with corners of
// the identical bit pattern, and kept so validation can count them. Facet normals are ignored.
#pragma once
#include <string>

#include "meshio/read_raw_mesh.h"

namespace offsetopt {

RawMesh read_stl(const std::string& name, const std::string& bytes);

// True when the size is exactly 84 + 50 * (count in the header).
bool looks_like_binary_stl(const std::string& bytes);

}  // namespace offsetopt
