// Openings through a written cavity (issue 20): drain holes for resin prints and the channel of a
// container (`--fix`/`--opening` with a contoured cavity), cut from the hollow solid (outer surface
// plus the cavity's shells reversed) by geometry/subtract_convex.h, so the result is one closed,
// oriented 2-manifold per piece of the outer surface, every cavity shell joined to the outside.
//
// Each opening is a cylinder approximated by a prism of `sides` sides (geometry/cylinder_prism.h):
//   - drain hole at a point P of the void (`--drain-hole X,Y,Z[,R]`): axis from P to the nearest
//     point Q of the outer surface, the inner cap at P, the outer cap R + 2·wall beyond Q;
//   - automatic drain hole (`--drain-holes auto`): one per cavity shell, at its lowest vertex p as
//     posed (the print's orientation): the inner cap at p moved into the void along the cavity's
//     inward vertex normal by min(R/2, 0.45 × the void's depth there), the axis from it to its
//     nearest outer point (the thinnest wall there);
//   - channel for a half-space region (x/y/z > or < V): along the region's axis, through the
//     centroid of the largest section of the outer surface at V (where that line has room for the
//     wall and a quarter more; else through the point of a 16 × 16 grid over that section with the
//     most room); its radius the smallest distance from the axis to the outer surface's sections
//     across the region (9 levels; the axis may leave the surface, passing it by the room beyond,
//     but not enter it again), less the wall
//     (capped by max_channel_radius when > 0), so the wall around it stays; it starts inside the
//     void (below the first cavity hit of every prism corner's ray, above the void's other side) and
//     leaves the bounding box by a wall.
//   - opening for a sphere region (centre C, radius R): from the void to the point Q of the outer
//     surface nearest C, its radius half the region's reach on the surface there
//     (√(R² − |Q − C|²) / 2), shrunk ×0.8 until every corner of its inner end lies in the void;
//     the inner end at the cavity's point P nearest Q, moved into the void along Q → P by half the
//     radius (at most 0.45 of the void's depth that way); the outer cap radius + 2·wall beyond Q.
// Every cut moves the prism sideways by 1e-5 of its radius (an automatic hole's axis starts at a
// cavity vertex, on lines of the contour's edges); a degenerate cut (a solid vertex on a prism
// plane, ...) turns it by 0.0137 rad, moves it along its axis by 1e-7 and sideways by another 1e-5
// of the radius, at most 8 tries.
//
// Lengths in the meshes' units. Every choice is deterministic.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mesh/mesh.h"
#include "shape/fix_region.h"

namespace offsetopt {

struct DrainHoleRequest {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double radius = -1.0;  // < 0: OpenCavityOptions::hole_radius
};

struct OpenCavityOptions {
  std::vector<DrainHoleRequest> holes;
  bool auto_holes = false;
  // PrusaSlicer's default drain hole: 4 mm across (radius 2), 6 mm deep (GLGizmoHollow's
  // m_new_hole_radius, m_new_hole_height); the depth here is whatever the wall needs.
  double hole_radius = 2.0;
  FixRegion opening;                  // Kind::none: no channel
  double max_channel_radius = -1.0;   // > 0: caps the channel's radius
  double wall = 0.0;                  // > 0
  int sides = 32;
  std::string check() const;
};

// The line a channel through the half-space `region` runs along (see above: chosen for a channel
// keeping `wall`), `direction` the region's axis pointing out of the object into the region (+z for
// z>V). None, with `why`, when no such line stays inside the outer surface across the region.
struct ChannelAxis {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();      // on the region's plane
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
};
std::optional<ChannelAxis> channel_axis(const Mesh& outer, const FixRegion& region, double wall, std::string& why);

struct CutOpening {
  std::string kind;                   // "drain hole", "auto drain hole", "channel", "opening" (a sphere region)
  Eigen::Vector3d inner = Eigen::Vector3d::Zero(), outer = Eigen::Vector3d::Zero();  // cap centres
  double radius = 0.0;
  int shell = -1;                     // auto: the cavity shell
  int tries = 1;
};

struct OpenedCavity {
  bool ok = false;
  std::string message;                // why not, when !ok
  Mesh solid;                         // one closed oriented mesh, normals out of the material
  std::vector<int> source_face;       // per face: the face of hollow_solid(outer, cavity) it copies, or -1
  std::vector<CutOpening> openings;
  int cavity_shells = 0;
  int pieces_before = 0, pieces_after = 0;  // connected shells of the hollow solid and of the result
  // Closed pieces of material the prisms cut loose (below 1e-3 of the largest piece's volume):
  // dropped, as they would fall out of the print.
  int chips_dropped = 0;
  // Channel: the height (z) of the lowest point where it leaves the outer surface: a liquid poured
  // in spills there.
  std::optional<double> spill_height;
};

// `outer` closed, outward; `cavity` the cavity's shells with normals out of the void (as
// cavity/contour_cavity.h writes them).
OpenedCavity open_cavity(const Mesh& outer, const Mesh& cavity, const OpenCavityOptions& options);

// The part of `mesh` (closed, outward) below the plane coordinate `axis` = `level` (above it when
// `keep_above`), closed by the cut: a box cutter through subtract_convex, its plane moved by 1e-9 of
// the box's size per degenerate try. False when 8 tries failed.
bool cut_by_plane(const Mesh& mesh, int axis, double level, bool keep_above, Mesh& out);

}  // namespace offsetopt
