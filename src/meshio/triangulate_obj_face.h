// Triangulation of one OBJ face, a planar (or nearly planar) polygon in 3-D, by ear clipping in
// its best-fit plane
// (Meisters 1975, "Polygons have ears"; the plane's normal is Newell's, Sutherland et al. 1974,
// which is robust for non-convex and slightly non-planar polygons). Used by the OBJ reader, whose
// polygons may have any number of corners and be non-convex (CAD caps, text, L shapes).
//
// The corners are projected onto the coordinate plane that drops the normal's dominant axis,
// oriented so the polygon runs counter-clockwise there. A corner is an ear when it is strictly
// convex and no other remaining corner (except ones at the same position as the ear's corners:
// bridged holes) lies inside or on the ear's triangle; the first ear in polygon order from the
// current corner is clipped. Triangles keep the polygon's corner order, so the orientation is the
// polygon's. Deterministic (plain double arithmetic in a fixed order).
// Special cases: a polygon with no reflex corner, or whose Newell normal is zero or not finite,
// is fan-triangulated (v0, vi, vi+1), exactly as before this reader clipped ears, so convex
// polygons give the same triangles as the other readers. When no ear exists (a self-intersecting
// outline) the first convex-or-flat corner is clipped anyway: n - 2 triangles always come out.
// Cost: O(n^2) point tests for ordinary polygons, O(n^3) at worst; `budget` is decreased by
// the tests made, and the status is budget_exhausted (no triangles) when it runs out.
// Not geometry/triangulate_polygons.h, the other ear clipper (flat base caps): that one takes
// exact 2-D loops with holes, refuses a loop without an ear and flips edges against slivers;
// a file's face may be slightly non-planar or self-intersecting and must still give n - 2
// triangles in the reader's fixed order (the meshes read, and so every output, depend on it).
#pragma once
#include <Eigen/Core>
#include <vector>

namespace offsetopt {

enum class PolygonTriangulationStatus { fan, ear_clipping, budget_exhausted };

// `points` are the polygon's corners in order (n >= 3). On return `triangles` holds 3 (n - 2)
// corner numbers into `points`.
PolygonTriangulationStatus triangulate_obj_face(const std::vector<Eigen::Vector3d>& points, std::vector<int>& triangles,
                                                long long& budget);

}  // namespace offsetopt
