// 3MF output (3MF Consortium, "3D Manufacturing Format, Core Specification" 1.3; namespace
// http://schemas.microsoft.com/3dmanufacturing/core/2015/02): a zip (io/zip_archive.h,
// stored entries, fixed timestamps) of [Content_Types].xml, _rels/.rels and 3D/3dmodel.model.
// The mesh is ONE object of type "model" whose <mesh> holds every shell (a printable solid's
// outer surface and its cavity shells), with one build item. Coordinates are shortest round-trip
// text (util/format_double.h), so equal meshes give byte-identical files.
#pragma once
#include <string>
#include <vector>

#include "mesh/mesh.h"

namespace offsetopt {

// The unit names of the 3MF core spec (ST_Unit), in the spec's order.
const std::vector<std::string>& units_3mf();

// True when `unit` is one of units_3mf().
bool is_unit_3mf(const std::string& unit);

// The package bytes. Throws MeshInputError for a non-finite coordinate (3MF numbers are finite)
// or an unknown unit, std::length_error when the model needs zip64 (4 GiB of XML).
std::string write_3mf(const Mesh& mesh, const std::string& unit = "millimeter");

}  // namespace offsetopt
