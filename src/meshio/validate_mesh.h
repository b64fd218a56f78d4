// Validation of a triangle mesh as a printable solid: every defect named and counted, with the
// first offending face or vertex. `offsetopt check` prints the result; load_mesh repairs what
// is safe and refuses the rest. Implements no paper; the checks are the usual ones for a
// closed, oriented 2-manifold (Botsch et al., "Polygon Mesh Processing", ch. 1).
//
// Definitions (faces and vertices numbered from 0 in file order, faces after triangulation):
//   empty mesh               no faces
//   non-finite coordinates   vertices with a NaN or infinite coordinate
//   coordinates too large    vertices with |x|, |y| or |z| > kMaxCoordinate (1e12): volume and
//                            inertia are products of up to five coordinates and must stay finite
//   vertex index out of range  faces with an index < 0 or >= #V
//   degenerate faces         a repeated vertex index
//   duplicate faces          faces over the same three vertices as an earlier face (either
//                            orientation); the count is of the later copies
//   boundary edges           edges of one face only (the mesh is not closed)
//   non-manifold edges       edges of three or more faces
//   non-manifold vertices    vertices whose faces form two or more fans joined only at the
//                            vertex (two cones touching at the tip)
//   inconsistent orientation edges of two faces that traverse it in the same direction
//   zero volume              closed shells enclosing |volume| <= 1e-12 * (bounding diagonal)^3
//   inside-out               closed shells whose signed volume has the wrong sign for their
//                            nesting depth: an outer shell must be positive, a cavity (a shell
//                            inside an odd number of others) negative
//   several components       more than one connected piece (faces sharing a vertex)
// Later checks need earlier ones: nothing after an out-of-range index; no area or volume with
// non-finite or too large coordinates; volumes only when closed, edge-manifold and consistently
// oriented. Unreferenced vertices are not a defect (reported as a note), nor are zero-area
// faces with three distinct (collinear) corners, exactly zero area in double arithmetic (a note
// with a count: OpenSCAD's STL exports close T-junctions with them; they add nothing to any
// volume integral and the cotan Laplacian mollifies them, geometry/intrinsic_mollification.h). Nesting is found by
// ray parity from a point on each shell (bounding boxes first, geometry/aabb.h; the ray test is
// geometry/ray_triangle.h), for up to 10,000 shells; beyond that every shell counts as outermost.
// Each check is its own function in validate_mesh.cpp, in the order above; validate_mesh()
// composes them.
// Limits of the readers (meshio/read_raw_mesh.h): files up to 2 GiB, regular files only; at most
// 2^25 (33,554,432) vertices and 2^25 triangles; OBJ polygons of any corner count (ear clipping
// with a work cap, meshio/triangulate_obj_face.h).
//
// Input policy (the README copies this table).
//   defect                        check        load_mesh (inspect, basis, skeleton, optimize)
//   syntax error, truncated file,
//     count beyond the file size  exit 2       refused (MeshInputError, exit 2)
//   empty mesh                    exit 2       refused
//   non-finite / too large coordinate  exit 2  refused, unless only unreferenced vertices
//   vertex index out of range     exit 2       refused
//   unsupported variant (binary
//     OFF, 4OFF, PLY tristrips)   exit 2       refused
//   polygon with > 3 corners      warning      fan-triangulated, warning (OBJ: any corner count;
//                                              non-convex ones ear-clipped in their plane)
//   OBJ mtllib, l, p, vt, vn, g,
//     o, s, usemtl statements     (ignored)    ignored; a warning for mtllib (never opened)
//                                              and for l/p elements
//   bytes after the data (binary
//     STL/PLY), text after the
//     last OFF face / PLY element warning      ignored, warning
//   ASCII STL without endsolid    warning      accepted, warning
//   unreferenced vertices         warning      dropped, warning
//   STL corners at one position   (welded)     welded silently (that is how STL stores vertices)
//   degenerate face, repeated
//     vertex (often after STL welding)  exit 2 dropped, warning; then the rest must validate
//   zero-area face with 3
//     distinct (collinear) vertices  warning   accepted, warning with the count (a valid
//                                              closed solid; the Laplacian mollifies them)
//   duplicate face, same
//     orientation                 exit 2       extra copies dropped, warning
//   duplicate face, opposite
//     orientation                 exit 2       refused (a zero-thickness sheet)
//   boundary edges                exit 2       refused (not a solid; no safe automatic fill)
//   non-manifold edges / vertices exit 2       refused
//   inconsistent orientation      exit 2       refused
//   zero volume                   exit 2       refused
//   inside-out (every shell)      exit 2       all faces flipped, warning (as slicers do)
//   inside-out (some shells only) exit 2       refused (overlapping parts or a wrong cavity:
//                                              the intent is ambiguous)
//   several components            exit 2       accepted with a warning when each is a closed,
//                                              correctly nested shell (separate parts, or a
//                                              solid with cavities); refused when
//                                              LoadOptions::single_component is set
// Several components: a slicer user prints multi-part files, and mass properties (volume,
// centre of mass, inertia) of several closed, correctly oriented and nested shells are exactly
// those of the solid they bound, so `inspect` accepts them. A command whose method assumes one
// connected surface (a spectral basis with a single constant mode, one meso-skeleton) sets
// LoadOptions::single_component and gets a clear refusal instead. Overlapping (intersecting)
// parts are not detected here (they need the BVH): the CLI layer finds self-intersecting
// face pairs and pinches with geometry/mesh_defects.h; `check` refuses them, the other commands
// warn, since an overlap counts twice in the mass.
#pragma once
#include <string>
#include <vector>

#include "mesh/mesh.h"

namespace offsetopt {

constexpr double kMaxCoordinate = 1e12;

enum class DefectKind {
  empty_mesh,
  non_finite_coordinate,
  coordinate_too_large,
  index_out_of_range,
  degenerate_face,
  duplicate_face,
  boundary_edge,
  non_manifold_edge,
  non_manifold_vertex,
  inconsistent_orientation,
  zero_volume,
  inside_out,
  overlapping_shells,
  several_components,
};

// One kind of defect: how many, and the first instance (smallest face or vertex number).
struct Defect {
  DefectKind kind = DefectKind::empty_mesh;
  long long count = 0;     // faces, vertices, edges, shells or components (see defect_unit)
  long long face = -1;     // first offending face, or -1
  long long vertex = -1;   // first offending vertex (vertex defects), or -1
  long long other_face = -1;                 // the face it conflicts with (duplicate, orientation)
  long long edge_from = -1, edge_to = -1;    // the offending edge (edge defects)
  double value = 0;  // coordinate, index, faces at the edge, fans, signed volume, components
  long long bound = -1;  // #V (index out of range), nesting depth (inside-out), #V (empty mesh),
                         // 1 when every shell is inside-out (overlapping shells)
};

struct MeshValidation {
  std::vector<Defect> defects;  // in DefectKind order, at most one entry per kind
  long long vertices = 0, faces = 0;
  long long edges = -1;                  // undirected edges, -1 when not computed
  long long unreferenced_vertices = 0;   // a note, not a defect
  long long first_unreferenced = -1;
  long long repeated_vertex_faces = 0;   // degenerate faces with a repeated index (load_mesh drops)
  long long zero_area_faces = 0;         // exactly zero area with 3 distinct corners (a note)
  long long first_zero_area_face = -1;
  long long same_orientation_duplicates = 0;  // later copies of a face in the same orientation
  // Faces load_mesh drops: repeated-vertex faces and same-orientation later copies, ascending.
  std::vector<long long> droppable_faces;
  int components = 0;                    // connected pieces (faces sharing a vertex)
  std::vector<int> face_component;       // per face, components numbered by first face; or empty
  std::vector<double> component_volume;  // signed, per component; empty unless computed
  std::vector<int> component_depth;      // shells containing each component; empty unless computed
  double volume = 0;                     // signed total; meaningful when volume_computed
  bool volume_computed = false;
  long long euler_characteristic = 0;    // V - E + F over referenced vertices, when edges >= 0
  long long genus = -1;                  // sum over components, for a closed 2-manifold; else -1

  bool valid() const { return defects.empty(); }
  const Defect* find(DefectKind kind) const;
};

MeshValidation validate_mesh(const Mesh& mesh);

// "boundary edges", "inside-out shells (negative volume)", ...: the name check prints.
const char* defect_name(DefectKind kind);
// "faces", "edges", "vertices", "shells" or "components".
const char* defect_unit(DefectKind kind);

// Where the reported numbers point back to: optional maps from the validated mesh's face and
// vertex numbers to those of the file (after load_mesh dropped faces or vertices), and the
// source line of each file face and vertex (text formats; empty otherwise).
struct DefectSource {
  const std::vector<long long>* face_origin = nullptr;
  const std::vector<long long>* vertex_origin = nullptr;
  const std::vector<int>* face_line = nullptr;
  const std::vector<int>* vertex_line = nullptr;
};

// One sentence about the first instance: "edge 3-7 belongs to one face only".
std::string describe_defect(const Defect& defect, const DefectSource& source = {});

// The line `check` prints after "Error: ": "<file>: boundary edges: 4 (first: face 3, line 20):
// edge 2-5 belongs to one face only".
std::string defect_report_line(const std::string& file, const Defect& defect, const DefectSource& source = {});

// The MeshInputError text of load_mesh: "<file>:<line>: <sentence>[ (N edges in all)]" for text
// formats, "<file>: <sentence>, face 17[ (N faces in all)]" otherwise.
std::string defect_error_message(const std::string& file, const Defect& defect, const DefectSource& source = {});

}  // namespace offsetopt
