// The closed polylines where a plane cuts a closed, outward-oriented triangle mesh: the outline of
// a planar cross-section, as a slicer computes a layer's contours (e.g. Minetto et al. 2017,
// "An optimal algorithm for 3D triangle mesh slicing"), here for an arbitrary plane.
//
// Vertices exactly on the plane are resolved by a symbolic rule (simulation of simplicity,
// Edelsbrunner and Mücke 1990): a vertex whose signed distance is 0 counts as lying on the
// positive side. Every edge is then either crossed or not, each crossed triangle gives exactly one
// segment, and the segments of a closed 2-manifold chain into closed loops. A crossing point is
// computed from its edge's endpoint on the positive side, so the two triangles sharing the edge
// get the same bits whatever the vertex numbering. Loops touching a vertex on the plane may
// contain zero-length segments.
//
// Orientation: with the plane's normal m pointing at the viewer and 2-D coordinates (u, v),
// u × v = m, each loop runs with the material on its left: a loop bounding material from outside
// is counter-clockwise (positive area), a loop bounding a void inside material is clockwise.
#pragma once
#include <vector>

#include <Eigen/Core>

#include "mesh/mesh.h"

namespace offsetopt {

struct SectionPlane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // m, pointing at the viewer; unit length
  double offset = 0.0;                                 // the plane is m · p = offset
  Eigen::Vector3d u = Eigen::Vector3d::UnitX();        // 2-D axes in the plane, u × v = m
  Eigen::Vector3d v = Eigen::Vector3d::UnitY();
};

// The plane y = y0 seen from −y: u = x, v = z (a front view).
SectionPlane xz_plane(double y0);
// The plane x = x0 seen from +x: u = y, v = z (a side view).
SectionPlane yz_plane(double x0);
// The plane z = z0 seen from +z: u = x, v = y (a top view).
SectionPlane xy_plane(double z0);

struct SectionLoop {
  std::vector<Eigen::Vector2d> points;  // (u, v); the closing segment back to points[0] is implied
  double signed_area = 0.0;             // shoelace: > 0 around material, < 0 around a void
  bool closed = true;                   // false only for a mesh that is not closed
};

enum class SectionStatus { ok, open_chain };

struct PlaneSection {
  SectionStatus status = SectionStatus::ok;
  std::vector<SectionLoop> loops;  // in the order of their first face
};

// Cuts `mesh` with `plane`. Deterministic: loops start at their lowest-numbered face and follow
// the mesh's orientation. A chain that cannot close (the mesh has a boundary) is returned open
// and the status says so.
PlaneSection plane_section(const Mesh& mesh, const SectionPlane& plane);

}  // namespace offsetopt
