// Defects of a closed mesh that validate_mesh (meshio/validate_mesh.h) does not check because
// they need the BVH: faces that cross each other, and pinches. `offsetopt check`
// refuses both (exit 2); the other commands accept them with a warning (meshio/load_input.h); the
// optimiser's verification compares the written cavity's pair count with the input's own.
//
// Self-intersections (find_self_intersections): pairs of faces (f, g), f < g, numbered as rows of
// mesh.F, whose closed triangles meet other than where the mesh joins them. A simultaneous
// traversal of the face BVH with itself (geometry/bvh.h), exact face boxes, then the exact pair
// rule of geometry/faces_intersect_exact.h (CGAL's self_intersections semantics), with corners
// compared by position (vertices at one position are one corner, as a reader that merges
// duplicate points sees them; the faces of a pinch touching at the pinch point are then not a
// pair, and find_pinches reports the pinch). Two things stay outside that rule:
//   - faces with collinear corners (exactly) have no plane and are not tested; CGAL lists each
//     as a pair (f, f), here they are counted apart (collinear_faces);
//   - a zero-area face with three distinct corners (a CAD T-junction filler) joins the faces
//     across its long edge at its middle corner: a pair whose only contact is that corner (through
//     chains of such faces) is not counted, where CGAL counts it.
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
  long long collinear_faces = 0;  // faces with collinear corners, not tested
};

// `threads` > 1: the search in two parts at once when neither part reaches a cap (else in one
// piece): the same report on any count.
SelfIntersectionReport find_self_intersections(const Mesh& mesh, std::size_t cap = 1000000, int threads = 1);

struct PinchReport {
  long long pairs = 0;  // vertex pairs at one position
  int first_vertex = -1, second_vertex = -1;  // the smallest pair (first < second), or -1
};

PinchReport find_pinches(const Mesh& mesh);

}  // namespace offsetopt
