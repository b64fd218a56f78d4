// Wavefront OBJ reader (v and f statements; everything else is ignored).
//
// tinyobjloader 2.0.0rc10 alone is unsafe on hostile input (see docs/design.md, "Known input
// pitfalls"), so reading is two passes over the bytes already in memory:
//  1. our own strict pass over every line: `v` takes 3 to 7 numbers (x y z [w] [r g b]), all
//     parsed in full with std::from_chars; `f` takes 3 or more corners `v`, `v/vt`, `v/vt/`,
//     `v//`, `v//vn` or `v/vt/vn` of whole decimal integers (empty texture and normal parts are
//     accepted: exporters write `2/2/`), index 0 refused, negative indices resolved against the
//     vertices seen so far; NUL bytes and malformed tokens are refused with the line number.
//  2. tinyobjloader parses a copy in which every line other than `v` and `f` is blanked (so it
//     never sees `mtllib`, `t`, `vw`, `l` or `p` and keeps the same line numbers), every `v`
//     line is `v 0 0 0` (its number parser overflows an int on an exponent such as
//     1e2147483648, undefined behaviour; it needs only the vertex count) and every `f` line keeps
//     only the vertex part of each corner, from memory, with a material reader that refuses
//     every file and triangulation off. Faces over 255 corners are blanked too (rc10 keeps the
//     corner count in a byte). Its face list must agree corner by corner with pass 1, or the
//     file is refused.
//  3. our own triangulation of every polygon, in its best-fit plane (meshio/triangulate_obj_face.h:
//     convex polygons fan-triangulated as by the other readers, others ear-clipped), never
//     tinyobjloader's. A polygon whose ear clipping would exceed the work cap (about 4e8 point
//     tests per file: a non-convex outline of tens of thousands of corners) is refused with its
//     line.
// Coordinates come from pass 1 because tinyobjloader's number parser is not correctly rounded
// (its result can differ from the nearest double in the last bits), and the project promises
// that a written OBJ reads back bit-identical.
#pragma once
#include <string>

#include "meshio/read_raw_mesh.h"

namespace offsetopt {

// `name` is used in error messages; `text` is the whole file.
RawMesh read_obj(const std::string& name, const std::string& text);

}  // namespace offsetopt
