// Verification of an optimised object as it will be printed (what the paper does not do): the
// goal's metrics recomputed from the final surfaces in input units, the bounds, the wall
// thickness measured as a distance, and intersections found through the BVH
// (geometry/intersecting_faces.h). The optimiser's exit status is decided here.
#pragma once
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "cavity/round_for_output.h"
#include "mesh/mesh.h"
#include "shape/goal.h"

namespace offsetopt {

// Where the surfaces are not printable as they are: vertices of inner faces that intersect other
// inner faces or cross the outer surface, and inner vertices closer to the outer surface than
// `thin_below` (away from fixed vertices and parts left solid). With `--cavity offset` the
// optimiser tightens the bounds of these vertices and solves again. `fixed` and `left_solid` are per
// vertex of a shared connectivity (inner and outer offsets of one mesh), or empty when the inner
// mesh is a cavity of its own.
struct SurfaceDefects {
  std::vector<int> intersecting_vertices;  // sorted, unique
  std::vector<int> thin_wall_vertices;     // sorted
  std::size_t self_intersection_pairs = 0, crossing_pairs = 0;
  bool truncated = false;
  double thinnest_wall = 0.0;  // infinity when nothing was measured
  int thinnest_vertex = -1;
  bool empty() const { return intersecting_vertices.empty() && thin_wall_vertices.empty(); }
};
// Per inner vertex, lower bounds of its distance to the outer surface, carried from one check of
// two surfaces to a check of the same surfaces rounded for output (round_for_output.h): `record`,
// when set, receives the first check's bounds (exact where a vertex was searched; 0 for the vertices
// not measured); `known`, when set, holds such bounds for the meshes now checked once `slack` (what
// rounding can change a distance, rounding_wall_margin) is taken off, and a vertex they put clear
// of every distance still to be found is not searched again. The result is the same with or
// without them (see the wall scan in verify_offsets.cpp).
struct WallBounds {
  const std::vector<double>* known = nullptr;
  double slack = 0.0;
  std::vector<double>* record = nullptr;
};
// `threads` (>= 1) splits the tree builds and the intersection searches; the result is the same
// for any count.
// `inner_self` and `inner_tree`, when given, are inner's own self-intersection search
// (self_intersections with a cap of 100000) and its tree (default leaf size): when nothing is fixed
// they are used instead of searching and building again (the search only when not truncated);
// `outer_tree` likewise, outer's tree (default leaf size).
SurfaceDefects find_surface_defects(const Mesh& outer, const Mesh& inner, const std::vector<char>& fixed,
                                    const std::vector<char>& left_solid, double thin_below, int threads = 2,
                                    const IntersectingFaces* inner_self = nullptr, const TriangleBvh* inner_tree = nullptr,
                                    const TriangleBvh* outer_tree = nullptr, const WallBounds& wall_bounds = {});

struct VerifyInput {
  const Mesh* outer = nullptr;  // outer surface (the input itself without outer offsets)
  const Mesh* inner = nullptr;  // the cavity's shells, normals out of the void: the inner offset
                                // surface (same connectivity as outer) or a contoured cavity
  GoalSpec goal;                // in input units (support polygon, axis point, target volume, ε)
  double diagonal = 1.0;        // input bounding-box diagonal
  double ground_tol = 0.0;      // input units
  double wall = 0.0;            // requested wall, input units
  std::vector<char> fixed;      // per vertex of a shared connectivity (the opening), or empty
  double bound_violation = 0.0; // largest violation of the enforced band, input units
  int threads = 2;              // for the intersection and wall searches; same result for any count
  bool goal_only = false;       // the goal's figures only: `valid` stays false and no validity
                                // figure is measured (a contour that will be corrected anyway)
  // Volume: the relative error allowed. Tighter for a void aimed at less than the target, whose
  // openings add the rest (optimize's cut_openings): the opened void is then checked at 1e-4.
  double volume_tolerance = 1e-4;
  // When outer and inner are the meshes as they read back from the files (round_for_output.h):
  // the defects the rounding made and could not undo, refused like any other.
  const RoundedForOutput* rounding = nullptr;
  StoredPrecision precision = StoredPrecision::exact;
  // When set, `outer` was moved (an outer offset, the input's connectivity) and is searched for
  // self-intersections: any pair not listed here (the input's own pairs, sorted, found by
  // cavity/new_self_intersections.h's rule) fails the verification. Null: `outer` is the input
  // itself, whose own pairs are the input's (named where it is loaded).
  const std::vector<std::pair<int, int>>* outer_own_pairs = nullptr;
  // stand-filled: the liquid, when an opening keeps it below the void's top (cavity/open_cavity.h);
  // its integrals replace the void's in the filled figures. Null: the whole void is filled.
  const Mesh* liquid = nullptr;
  // The wall's per-vertex bounds to record from this check or to start it from (WallBounds above).
  WallBounds wall_bounds;
};

// Whether the solid stands on its support polygon (mass/stability.h), input units.
struct StabilityFigures {
  double com_margin = 0.0;         // distance of the centre of mass inside the polygon (< 0: outside)
  double tipping_angle_deg = 0.0;
  bool stands = false;
};

// The goal's figures measured on the solid as written, input units. Which of the goal-specific
// ones are measured depends on `goal` (the others keep their zero values).
struct GoalFigures {
  GoalKind goal = GoalKind::stand;
  double mass = 0.0;               // of the material (density 1)
  double void_volume = 0.0;
  double outer_volume = 0.0;
  Eigen::Vector3d center_of_mass = Eigen::Vector3d::Zero();
  // stand, stand-filled: empty; stand-filled: filled, with the filled centre of mass.
  StabilityFigures empty, filled;
  Eigen::Vector3d filled_center_of_mass = Eigen::Vector3d::Zero();
  // roly-poly: the sphere centre; spin: the tip.
  Eigen::Vector3d axis_point = Eigen::Vector3d::Zero();
  double com_off_axis = 0.0;       // roly-poly, spin: off the vertical axis through axis_point
  double com_below_center = 0.0;   // roly-poly
  // spin
  double izx_over_izz = 0.0, iyz_over_izz = 0.0;
  Eigen::Vector3d principal_moments = Eigen::Vector3d::Zero();
  double spin_axis_tilt_deg = 0.0;
  bool spin_axis_is_largest_moment = false;
  // volume
  double target_volume = 0.0, volume_relative_error = 0.0;
  // float
  Eigen::Vector3d center_of_buoyancy = Eigen::Vector3d::Zero();
  double buoyancy_minus_weight = 0.0, com_off_buoyancy_axis = 0.0, com_below_buoyancy = 0.0;
};

// What makes the solid printable or not, input units.
struct ValidityFigures {
  long long inner_self_intersections = 0;  // face pairs (at most the search's cap)
  long long inner_outer_crossings = 0;
  long long cavity_unmatched_edges = 0;
  // Face pairs of a moved outer surface crossing each other that the input did not have (at most
  // the search's cap), and how many of the input's own it kept; absent when the outer surface is
  // the input (VerifyInput::outer_own_pairs null).
  std::optional<long long> outer_new_self_intersections, outer_own_self_intersections;
  double requested_wall = 0.0;
  std::optional<double> min_wall_measured;  // absent when no cavity vertex was measured
  int min_wall_vertex = -1;
  double largest_bound_violation = 0.0;
  // The precision the surfaces were verified at (that of the files written) and what rounding to
  // it took: vertices moved off their nearest float32 point, defects it left (0 when verified).
  StoredPrecision precision = StoredPrecision::exact;
  int vertices_moved_for_rounding = 0;
  long long rounding_new_defects = 0;
};

struct Verification {
  bool goal_met = false;
  bool valid = false;
  std::vector<std::string> failures;  // one line each, empty when goal_met && valid
  GoalFigures goal;
  std::optional<ValidityFigures> validity;  // absent when VerifyInput::goal_only
};

// Tolerances (relative to the diagonal unless stated): centre-of-mass positions 1e-4,
// inertia products 1e-4 of Izz, principal-axis tilt 0.5°, volume 1e-4 relative, buoyancy
// balance 1e-3 of the mass; the wall measured from every cavity vertex (but those of the opening,
// which lie on the outer surface) to the outer surface at least the requested one (1e-9 relative
// for rounding), no exemptions; no self-intersection of the cavity and no cavity/outer crossing;
// with a moved outer surface, no self-intersection of it that the input lacked.
Verification verify_offsets(const VerifyInput& input);

// A contoured cavity as it will be written: `outer` and `cavity` rounded to `precision`
// (cavity/round_for_output.h) and verified with `input`'s goal and tolerances (its outer, inner
// and rounding are replaced), and invalid when the contour found `faces_below_wall` faces closer
// to the outer surface than the wall between their vertices (the verification measures vertices).
struct VerifiedCavity {
  RoundedForOutput rounded;
  Verification verification;
};
VerifiedCavity verify_written_cavity(VerifyInput input, const Mesh& outer, const Mesh& cavity, int faces_below_wall,
                                    StoredPrecision precision);

}  // namespace offsetopt
