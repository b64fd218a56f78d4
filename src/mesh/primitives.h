// Closed, outward-oriented triangle meshes built procedurally: the shapes tests check against
// closed-form values and the raw material of the demo meshes. All trigonometry goes through
// util/det_math so the vertices are bit-identical on every machine.
#pragma once
#include <utility>
#include <vector>

#include "mesh/mesh.h"

namespace offsetopt {

// Icosahedron centred at the origin, subdivided `subdivisions` times (each step x4 faces),
// vertices projected to the sphere of `radius`. #V = 10*4^s + 2.
Mesh make_icosphere(double radius, int subdivisions);

// Axis-aligned box [lo, hi] with 8 vertices and 12 triangles.
Mesh make_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

// Ring torus around the z axis: major radius R, tube radius r, `major_segments` x
// `minor_segments` vertices.
Mesh make_torus(double major_radius, double minor_radius, int major_segments, int minor_segments);

// Surface of revolution about the z axis. `profile` lists (radius, z) from the bottom pole to the
// top pole; the first and last radius must be 0 (they become single pole vertices) and the
// others > 0. `segments` vertices per ring, the first at angle 0 (+x).
Mesh make_revolution(const std::vector<std::pair<double, double>>& profile, int segments);

// Capsule along z: cylinder of `radius` between z = -half_length and +half_length, capped by
// hemispheres. `segments` around, `cap_rings` latitude rings per hemisphere, `body_rings`
// rings splitting the cylinder.
Mesh make_capsule(double radius, double half_length, int segments, int cap_rings, int body_rings);

// Closed cylinder along z from z0 to z1, flat caps meshed as rings shrinking to a centre pole.
Mesh make_cylinder(double radius, double z0, double z1, int segments, int body_rings, int cap_rings);

}  // namespace offsetopt
