// Buoyancy of a floating solid held upright (no heel): the displaced volume below a horizontal
// waterline and the level at which it balances the weight (Archimedes; the float goal of
// Musialski et al. 2015, eq. 9, wants the centre of mass below the centre of buoyancy).
//
// The part of a closed mesh below z = level has as boundary the clipped triangles plus a flat cap
// on the plane. Measured from an origin on that plane, the cap's tetrahedra are flat, so the
// divergence-theorem sum over the clipped triangles alone is exact (mass/volume_integrals.h).
#pragma once
#include <string>

#include <Eigen/Core>

#include "mass/volume_integrals.h"

namespace offsetopt {

// Raw integrals of the solid below the plane z = level, measured from the origin
// (mean vertex x, mean vertex y, level).
VolumeIntegrals volume_integrals_below(const Mesh& mesh, double level);

struct FloatingEquilibrium {
  enum class Status { floats, sinks };
  Status status = Status::sinks;
  double waterline = 0.0;          // z of the fluid surface (the mesh's top when it sinks)
  double displaced_volume = 0.0;   // volume below the waterline
  Eigen::Vector3d center_of_buoyancy = Eigen::Vector3d::Zero();  // centroid of that volume
  int iterations = 0;              // bisection steps taken
};

struct FloatingOptions {
  double fluid_density = 1.0;     // relative to the solid's density 1
  int max_iterations = 200;       // bisection cap
  double level_tolerance = 1e-12; // relative to the mesh's height

  // Empty when valid, else what is wrong: fluid_density, max_iterations and level_tolerance must
  // be > 0 (floating_equilibrium throws it as std::invalid_argument).
  std::string check() const;
};

// The waterline at which fluid_density * displaced_volume = mass for the outer surface `outer`
// of an object of the given mass (a hollow object: pass its outer surface and the shell's mass).
// Sinks when mass >= fluid_density * volume(outer).
FloatingEquilibrium floating_equilibrium(const Mesh& outer, double mass, const FloatingOptions& options = {});

}  // namespace offsetopt
