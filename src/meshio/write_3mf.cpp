#include "meshio/write_3mf.h"

#include <charconv>
#include <cmath>

#include "io/zip_archive.h"
#include "meshio/load_mesh.h"
#include "util/format_double.h"

namespace offsetopt {

const std::vector<std::string>& units_3mf() {
  static const std::vector<std::string> units = {"micron", "millimeter", "centimeter", "inch", "foot", "meter"};
  return units;
}

bool is_unit_3mf(const std::string& unit) {
  for (const std::string& u : units_3mf())
    if (u == unit) return true;
  return false;
}

std::string write_3mf(const Mesh& mesh, const std::string& unit) {
  if (!is_unit_3mf(unit)) throw MeshInputError("unknown 3MF unit '" + unit + "'");
  std::string model;
  model.reserve(static_cast<std::size_t>(mesh.V.rows()) * 80 + static_cast<std::size_t>(mesh.F.rows()) * 48 + 1024);
  model +=
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<model unit=\"" + unit + "\" xml:lang=\"en-US\" xmlns=\"http://schemas.microsoft.com/3dmanufacturing/core/2015/02\">\n"
      " <metadata name=\"Application\">offsetopt</metadata>\n"
      " <resources>\n"
      "  <object id=\"1\" type=\"model\">\n"
      "   <mesh>\n"
      "    <vertices>\n";
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    static const char* const kAttr[3] = {"     <vertex x=\"", "\" y=\"", "\" z=\""};
    for (int c = 0; c < 3; ++c) {
      const double value = mesh.V(i, c);
      if (!std::isfinite(value)) throw MeshInputError("vertex " + std::to_string(i) + " is not finite; 3MF cannot hold it");
      model += kAttr[c];
      append_double(model, value == 0.0 ? 0.0 : value);  // "-0" is valid, but "0" reads the same everywhere
    }
    model += "\"/>\n";
  }
  model +=
      "    </vertices>\n"
      "    <triangles>\n";
  char buffer[16];
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    static const char* const kAttr[3] = {"     <triangle v1=\"", "\" v2=\"", "\" v3=\""};
    for (int c = 0; c < 3; ++c) {
      model += kAttr[c];
      const auto end = std::to_chars(buffer, buffer + sizeof buffer, mesh.F(f, c)).ptr;
      model.append(buffer, end);
    }
    model += "\"/>\n";
  }
  model +=
      "    </triangles>\n"
      "   </mesh>\n"
      "  </object>\n"
      " </resources>\n"
      " <build>\n"
      "  <item objectid=\"1\"/>\n"
      " </build>\n"
      "</model>\n";
  std::vector<ZipEntry> entries(3);
  entries[0].name = "[Content_Types].xml";
  entries[0].data =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<Types xmlns=\"http://schemas.openxmlformats.org/package/2006/content-types\">\n"
      " <Default Extension=\"rels\" ContentType=\"application/vnd.openxmlformats-package.relationships+xml\"/>\n"
      " <Default Extension=\"model\" ContentType=\"application/vnd.ms-package.3dmanufacturing-3dmodel+xml\"/>\n"
      "</Types>\n";
  entries[1].name = "_rels/.rels";
  entries[1].data =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<Relationships xmlns=\"http://schemas.openxmlformats.org/package/2006/relationships\">\n"
      " <Relationship Target=\"/3D/3dmodel.model\" Id=\"rel0\" Type=\"http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel\"/>\n"
      "</Relationships>\n";
  entries[2].name = "3D/3dmodel.model";
  entries[2].data = std::move(model);
  return write_zip(entries);
}

}  // namespace offsetopt
