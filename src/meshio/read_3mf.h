// 3MF reader (3MF Core Specification 1.3; OPC part names, ECMA-376 part 2): the zip container
// (io/zip_archive.h, stored or deflate entries), the model part named by _rels/.rels (or
// 3D/3dmodel.model when there is no such relationship), its <object> meshes and <components>,
// and the <build> items with their transforms. Components may live in other model parts of the
// package (the production extension's p:path, as Bambu Studio and OrcaSlicer write them).
//
// Every build item becomes triangles in one RawMesh (item and component transforms applied; a
// transform with negative determinant mirrors, so its triangles are reversed to keep them facing
// out). Objects of type support, solidsupport, surface or other are left out with a warning.
// Coordinates are kept in the file's unit (RawMesh::unit names it); a unit other than millimeter
// gives a warning.
// Materials, colours, metadata and unknown extension elements are ignored.
//
// Limits as for the other readers (meshio/read_raw_mesh.h): the inflated parts together stay
// within kMaxFileBytes, vertex and triangle counts within kMaxVertices and kMaxFaces (also per
// part, before the build), components nest at most 32 deep (which also ends reference cycles), and the build places at
// most 2^20 object instances holding at most 64 times the vertices the parts store (plus 65,536),
// so memory stays proportional to the inflated bytes.
// A triangle index beyond its object's vertices is refused here, since after the objects are
// merged it would silently name another object's vertex. Messages read
// "<file>: <entry>: line <n>: <what>" or "<file>: <what> (... byte offset)".
#pragma once
#include <string>

#include "meshio/read_raw_mesh.h"

namespace offsetopt {

RawMesh read_3mf(const std::string& name, const std::string& bytes);

// True when `bytes` starts like a zip archive (a local file header).
bool looks_like_zip(const std::string& bytes);

}  // namespace offsetopt
