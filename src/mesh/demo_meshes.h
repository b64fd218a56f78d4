// Procedural demo meshes, one per optimisation goal of Musialski et al. 2015 (section 6), plus
// plain shapes for tests. Deterministic (util/det_math only, no libm trigonometry), closed,
// outward-oriented 2-manifolds of 2k-6k vertices (top-coarse: 770), z up, resting on z = 0 where they are meant to
// stand. Every deformation applied is a bijection of space (a shear along x depending on z, a
// radial scaling per horizontal slice, a swept circle in disjoint meridian half-planes), so no
// mesh intersects itself. Units are millimetres (a printable size).
//
//   bottle    leaning bottle (paper fig. 1): flat circular base on z = 0, body sheared x += k z so
//             the solid's centre of mass projects outside the base; a hollow body with a thick
//             solid bottom stands (make_demo_cavity("bottle")).
//   top       asymmetric spinning top: a single pole tip at (0, 0, 0), a lump on the +x side of
//             its rim, so the solid's centre of mass is off the tip axis and Izx != 0.
//   rolypoly  hemisphere of radius 30 (centre (0, 0, 30)) under a figure; solid cz > 30.
//   buoy      round hull, ogive deck, mast and lamp; sinks when solid in fluid of density 0.806,
//             floats upright (centre of mass below the centre of buoyancy) with a void of about
//             28% of its volume in the upper hull.
//   handle    genus-1 ring whose tube radius varies from 12 to 2 (thinner than two walls of 1%
//             of the bounding-box diagonal), lying flat on z = 0.
//   sphere    icosphere of radius 30, 4 subdivisions (2562 vertices).
//   capsule   capsule of radius 15, standing on its lower pole.
//   torus     ring torus R = 30, r = 10, lying flat.
//   top-coarse  the top with half the profile steps and 32 segments: 770 vertices, the size of
//             the model of the paper's figure 10 (k against objective and time).
#pragma once
#include <string>
#include <vector>

#include "mesh/mesh.h"

namespace offsetopt {

// The names make_demo_mesh accepts, in a fixed order.
std::vector<std::string> demo_mesh_names();

// Throws std::invalid_argument for an unknown name. `detail` in [0.25, 32] multiplies the ring
// and segment counts of the revolution demos (bottle, top, rolypoly, buoy; vertex count about
// detail² times), for benchmarks at other sizes; 1 gives the committed meshes.
Mesh make_demo_mesh(const std::string& name, double detail = 1.0);

// A hand-made inner surface strictly inside make_demo_mesh(name), for the goal demos "bottle",
// "rolypoly", "buoy" and "top": removing the solid it bounds shows the goal is reachable by
// carving (the tests check that). Where it follows the outer surface the wall is about 1% of the
// bounding-box diagonal (at least 0.95% at every cavity vertex, measured by the tests); the
// bottle keeps a thick solid bottom, the roly-poly most of its hemisphere, the buoy its lower
// hull. For "top" it is an ellipsoidal lens inside the lump side of the rim (convex, so any copy
// scaled about its centroid by a factor in (0, 1] stays inside).
// Throws std::invalid_argument for other names.
Mesh make_demo_cavity(const std::string& name);

}  // namespace offsetopt
