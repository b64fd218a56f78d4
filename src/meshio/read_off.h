// OFF reader (Geomview Object File Format, ASCII).
//
// Header keyword OFF with optional ST/C/N prefixes (COFF, NOFF, STOFF, ...); 4OFF, nOFF and
// "OFF BINARY" are refused. The counts "#V #F [#E]" may follow on the same line or the next.
// '#' starts a comment anywhere. One vertex per line (x y z, further numbers such as colours
// ignored) and one polygon per line ("n i1 ... in", further numbers ignored); polygons are
// fan-triangulated. The counts are checked against the file size before anything is allocated:
// each vertex needs at least 6 bytes ("0 0 0\n") and each face 8 ("3 0 1 2\n").
#pragma once
#include <string>

#include "meshio/read_raw_mesh.h"

namespace offsetopt {

RawMesh read_off(const std::string& name, const std::string& text);

}  // namespace offsetopt
