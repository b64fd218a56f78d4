// Defects of a closed mesh that validate_mesh (meshio/validate_mesh.h) does not check because
// they need the BVH: faces that cross each other, and pinches. `offsetopt check`
// refuses both (exit 2); the other commands accept them with a warning (cli/cli_support.h); the
// optimiser's verification compares the written cavity's pair count with the input's own.
//
// Self-intersections (find_self_intersections): pairs of faces (f, g), f < g, numbered as rows of
// mesh.F, whose closed triangles meet other than where the mesh joins them. A simultaneous
// traversal of the face BVH with itself (geometry/bvh.h), exact face boxes, then a pair rule
// like geometry/intersecting_faces.h's, with these differences:
//   - corners are compared by position (vertices at one position count as one corner), so the
//     faces of a pinch touching at the pinch point are not a pair (find_pinches reports those);
//   - zero-area faces with three distinct collinear corners (CAD T-junction fillers) are not
//     tested themselves, and their middle corner counts as a corner of every face across the
//     edge it lies on (through chains of such faces), so the faces meeting at a T-junction are
//     joined as if they shared it;
//   - no shared corner: any contact counts, decided with corners within a relative 1e-12 of the
//     other face's plane counted as on it (plain Guigue-Devillers, triangle_triangle.h, takes
//     their signs from rounding and reported 1 to 134 false pairs on each demo mesh of
//     revolution, whose cone strips put corners exactly on other faces' planes), then the two
//     intervals on the planes' common line (or, coplanar, a 2-D test with snapped orientations);
//   - one shared corner: the edges opposite it (or, for a corner one face has only on an edge,
//     that face's other two edges) must meet the other face; two shared corners: the faces
//     count only when folded onto each other (normals opposite within 1e-9 rad); three: a
//     duplicate, always a pair (as in intersecting_faces.h).
// Plain double arithmetic: faces that nearly touch (within the tolerance) may go either way.
// Stops after `cap` pairs, or after the candidate pairs below (work_cap_reached; truncated
// then, and the first pair is the smallest of those found).
// Cost: O(F log F) plus the overlapping face boxes; 0.75 to 2.1 s for the 346k faces of the
// Armadillo on the shared 2-core machine (README), one thread. Requires indices in range and
// finite coordinates (else an empty report).
//
// Pinches (find_pinches): pairs of distinct referenced vertices (i, j), i < j, at exactly the same
// position and not joined by an edge: on a topological 2-manifold, two fans that touch at that
// one point (two cubes sharing a corner written twice, a scan's pinched-off neck). Vertices
// sorted by position; O(V log V).
#pragma once
#include <cstddef>

#include "mesh/mesh.h"

namespace offsetopt {

// Face pairs in leaves whose node boxes overlap that the search may visit: the larger of this
// and kSelfIntersectionCandidatesPerFace per face. Real meshes visit about 15 per face (the
// Armadillo: 5.4 million for 346k faces); a hostile file of long crossing needles, or a large
// shell around many small ones, about F²/2 (fuzz/make_hostile.py's tets_in_big_shell.obj: the
// cap of 5.6 million is reached in 0.7 s; 2e7 took 4.8 s, 92 s under ASan).
constexpr long long kMinSelfIntersectionCandidates = 2000000;
constexpr long long kSelfIntersectionCandidatesPerFace = 40;

struct SelfIntersectionReport {
  long long pairs = 0;     // face pairs found, at most the cap
  bool truncated = false;  // stopped at the cap or the work cap: there may be more
  bool work_cap_reached = false;  // stopped at the candidate-pair cap above
  long long candidate_pairs = 0;  // leaf face pairs visited (the cost)
  int first_face = -1, second_face = -1;  // the smallest pair found (first < second), or -1
};

SelfIntersectionReport find_self_intersections(const Mesh& mesh, std::size_t cap = 1000000);

// The test find_self_intersections applies to two faces without a shared corner, for callers
// whose faces are unrelated (two meshes, e.g. a cavity against the outer surface): closed
// triangles, touching counts, corners within a relative 1e-12 of the other plane count as on
// it. Zero-area triangles are tested as their edges (triangle_triangle.h).
bool separate_triangles_meet(const Eigen::Vector3d a[3], const Eigen::Vector3d b[3]);

struct PinchReport {
  long long pairs = 0;  // vertex pairs at one position
  int first_vertex = -1, second_vertex = -1;  // the smallest pair (first < second), or -1
};

PinchReport find_pinches(const Mesh& mesh);

}  // namespace offsetopt
