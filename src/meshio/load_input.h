// The input boundary every command but `check` goes through: load_mesh (meshio/load_mesh.h),
// then the geometric defects validate_mesh does not check (geometry/mesh_defects.h). Faces that
// cross each other and pinches are accepted, each with one warning naming the count and the first
// pair in the file's numbering; the searches' reports travel with the mesh so that nothing after
// the boundary searches the same mesh again (optimize_offsets takes the self-intersection count).
// `check` refuses both defects and words them with the same describe_* functions.
#pragma once
#include <string>
#include <vector>

#include "geometry/mesh_defects.h"
#include "meshio/load_mesh.h"

namespace offsetopt {

struct InputMesh : LoadedMesh {
  SelfIntersectionReport self_intersections;  // of `mesh`, capped at 10^6 pairs
  PinchReport pinches;
};

InputMesh load_input(const std::string& path, const LoadOptions& options = {});

// "3 self-intersecting face pairs (first: faces 10 and 52, lines 30 and 71; faces numbered from
// 0 in file order after triangulation)". `face_origin` maps the mesh's faces to the file's (empty:
// the same); `face_line` gives each file face's source line (empty: binary format).
std::string describe_self_intersections(const SelfIntersectionReport& report, const std::vector<long long>& face_origin,
                                        const std::vector<int>& face_line);
// "1 pinch: vertex pairs at one position whose fans touch only there (first: vertices 3 and 9,
// lines 4 and 10)".
std::string describe_pinches(const PinchReport& report, const std::vector<long long>& vertex_origin,
                             const std::vector<int>& vertex_line);

}  // namespace offsetopt
