#include "meshio/load_mesh.h"

#include <algorithm>

#include "meshio/validate_mesh.h"
#include "util/format_double.h"

namespace offsetopt {

namespace {

std::string plural(long long n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

std::string where_face(long long f, const std::vector<int>& face_line) {
  std::string out = "face " + std::to_string(f);
  if (f >= 0 && f < static_cast<long long>(face_line.size())) out += ", line " + std::to_string(face_line[static_cast<std::size_t>(f)]);
  return out;
}

}  // namespace

LoadedMesh load_raw_mesh(const std::string& name, RawMesh raw, const LoadOptions& options) {
  LoadedMesh out;
  out.format = format_name(raw.format);
  out.unit = raw.unit;
  out.warnings = std::move(raw.warnings);
  Mesh mesh{std::move(raw.V), std::move(raw.F)};
  const DefectSource file_numbering{nullptr, nullptr, &raw.face_line, &raw.vertex_line};

  MeshValidation validation = validate_mesh(mesh);
  // Without valid indices nothing can be repaired.
  for (const DefectKind kind : {DefectKind::empty_mesh, DefectKind::index_out_of_range})
    if (const Defect* d = validation.find(kind)) throw MeshInputError(defect_error_message(name, *d, file_numbering));

  // Safe repairs: drop faces that repeat a vertex and same-orientation copies of a face, then
  // vertices no face uses. Each maps back to file numbering for later messages.
  std::vector<long long> face_origin, vertex_origin;
  const bool drop_faces = !validation.droppable_faces.empty();
  const bool drop_vertices = drop_faces || validation.unreferenced_vertices > 0;
  if (drop_faces) {
    const long long repeated = validation.repeated_vertex_faces, copies = validation.same_orientation_duplicates;
    if (repeated > 0) {
      long long first = -1;
      for (const long long f : validation.droppable_faces)
        if (mesh.F(f, 0) == mesh.F(f, 1) || mesh.F(f, 1) == mesh.F(f, 2) || mesh.F(f, 0) == mesh.F(f, 2)) {
          first = f;
          break;
        }
      out.warnings.push_back("dropped " + plural(repeated, "degenerate face", "degenerate faces") +
                             " with a repeated vertex (first: " + where_face(first, raw.face_line) + ")");
    }
    if (copies > 0) {
      const Defect* d = validation.find(DefectKind::duplicate_face);
      std::string first;
      if (d && d->value > 0) first = " (first: " + where_face(d->face, raw.face_line) + ", a copy of face " + std::to_string(d->other_face) + ")";
      out.warnings.push_back("dropped " + plural(copies, "duplicate face", "duplicate faces") + first);
    }
    Faces kept(mesh.F.rows() - static_cast<Eigen::Index>(validation.droppable_faces.size()), 3);
    std::size_t next_drop = 0;
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
      if (next_drop < validation.droppable_faces.size() && validation.droppable_faces[next_drop] == f) {
        ++next_drop;
        continue;
      }
      kept.row(static_cast<Eigen::Index>(face_origin.size())) = mesh.F.row(f);
      face_origin.push_back(f);
    }
    mesh.F = std::move(kept);
  }
  if (drop_vertices) {
    std::vector<int> new_index(static_cast<std::size_t>(mesh.V.rows()), -1);
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
      for (int k = 0; k < 3; ++k) new_index[static_cast<std::size_t>(mesh.F(f, k))] = 0;
    for (Eigen::Index v = 0; v < mesh.V.rows(); ++v)
      if (new_index[static_cast<std::size_t>(v)] == 0) {
        new_index[static_cast<std::size_t>(v)] = static_cast<int>(vertex_origin.size());
        vertex_origin.push_back(v);
      }
    const long long dropped = mesh.V.rows() - static_cast<long long>(vertex_origin.size());
    if (dropped > 0) {
      long long first = -1;
      for (Eigen::Index v = 0; v < mesh.V.rows() && first < 0; ++v)
        if (new_index[static_cast<std::size_t>(v)] < 0) first = v;
      out.warnings.push_back("dropped " + plural(dropped, "unreferenced vertex", "unreferenced vertices") +
                             " (first: vertex " + std::to_string(first) + ")");
      Vertices kept(static_cast<Eigen::Index>(vertex_origin.size()), 3);
      for (std::size_t i = 0; i < vertex_origin.size(); ++i) kept.row(static_cast<Eigen::Index>(i)) = mesh.V.row(vertex_origin[i]);
      mesh.V = std::move(kept);
      for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
        for (int k = 0; k < 3; ++k) mesh.F(f, k) = new_index[static_cast<std::size_t>(mesh.F(f, k))];
    } else {
      vertex_origin.clear();
    }
  }
  if (drop_faces || !vertex_origin.empty()) validation = validate_mesh(mesh);
  const DefectSource source{face_origin.empty() ? nullptr : &face_origin, vertex_origin.empty() ? nullptr : &vertex_origin,
                            &raw.face_line, &raw.vertex_line};

  for (const Defect& d : validation.defects) {
    if (d.kind == DefectKind::inside_out || d.kind == DefectKind::several_components) continue;
    throw MeshInputError(defect_error_message(name, d, source));
  }
  if (const Defect* inverted = validation.find(DefectKind::inside_out)) {
    const bool every_shell = inverted->count == validation.components;
    if (!every_shell || !options.flip_inside_out) {
      std::string message = defect_error_message(name, *inverted, source);
      if (!every_shell) message += "; other shells are oriented correctly, so flipping all faces would not fix it";
      throw MeshInputError(message);
    }
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) std::swap(mesh.F(f, 1), mesh.F(f, 2));
    out.warnings.push_back("mesh is inside-out (signed volume " + format_double(validation.volume) +
                           "); every face flipped");
  }
  if (validation.zero_area_faces > 0) {
    long long first = validation.first_zero_area_face;
    if (!face_origin.empty()) first = face_origin[static_cast<std::size_t>(first)];
    out.warnings.push_back(plural(validation.zero_area_faces, "zero-area face", "zero-area faces") +
                           " with three distinct collinear corners (first: " + where_face(first, raw.face_line) +
                           "); kept: they add nothing to the volume, and the Laplacian mollifies them");
  }
  out.components = validation.components;
  out.face_origin = std::move(face_origin);
  out.vertex_origin = std::move(vertex_origin);
  out.face_line = std::move(raw.face_line);
  out.vertex_line = std::move(raw.vertex_line);
  if (validation.components > 1) {
    const Defect* several = validation.find(DefectKind::several_components);
    if (options.single_component) {
      throw MeshInputError(defect_error_message(name, *several, source) +
                           "; this command needs one connected surface (split the file into parts)");
    }
    out.warnings.push_back(std::to_string(validation.components) +
                           " separate closed shells (parts or cavities); treated as one solid");
  }
  out.mesh = std::move(mesh);
  return out;
}

LoadedMesh load_mesh(const std::string& path, const LoadOptions& options) {
  return load_raw_mesh(path, read_raw_mesh(path), options);
}

}  // namespace offsetopt
