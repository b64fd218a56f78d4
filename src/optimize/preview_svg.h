// A picture of a printable solid and its goal: a self-contained SVG (no scripts, fonts, links or
// images from outside the file) with two vertical cross-sections through the centre of mass
// (xz and yz) showing material, cavity and wall, a top view with the support polygon, the margin
// and the centre of mass before and after, and what the goal of Musialski et al. 2015 (section 6)
// needs besides: the tipping angle (stand, Prévost et al. 2013), the sphere centre (roly-poly),
// the spin axis and the principal moments (spin), the waterline and the centre of buoyancy
// (float), the void volume (volume).
//
// Every view shares one scale (equal in x and y, a scale bar in input units). Each view's group
// carries its mapping as data-origin-x, data-origin-y and data-scale: a point (u, v) of the view
// is drawn at (origin-x + scale·u, origin-y − scale·v) in SVG pixels (1 user unit = 1 px), so a
// test can check rendered pixels against model coordinates. The markers and the cavity have
// colours used for nothing else inside the views (see kPreview*Colour).
#pragma once
#include <string>

#include <Eigen/Core>

#include "mesh/mesh.h"
#include "shape/goal.h"

namespace offsetopt {

// Colours with a single meaning inside the views (the legend repeats them outside).
inline constexpr const char* kPreviewMaterialColour = "#9fb6d3";
inline constexpr const char* kPreviewCavityColour = "#ffd34d";
inline constexpr const char* kPreviewComAfterColour = "#ff00ff";
inline constexpr const char* kPreviewComBeforeColour = "#00b050";
inline constexpr const char* kPreviewOpeningColour = "#ff7f00";

struct PreviewOptions {
  double view_height = 320.0;   // px: the tallest view
  double views_width = 900.0;   // px: the three views side by side, at most
  double marker_radius = 4.5;   // px
  int bisection_cap = 200;      // waterline search (float)

  // Empty when the options are usable, else what is wrong.
  std::string check() const;
};

// What the picture needs besides the solid: the goal and its parameters as the optimize report
// states them (cli/write_preview.h reads them from a report). Lengths in input units; a negative length means "not given".
struct PreviewInput {
  GoalKind goal = GoalKind::stand;
  double margin = 0.0;
  double ground_tol = -1.0;      // negative: the default of mass/stability.h
  double fill_density = 1.0;     // stand-filled
  double fluid_density = -1.0;   // float
  double target_volume = -1.0;   // volume
  bool has_before_com = false;
  Eigen::Vector3d before_com = Eigen::Vector3d::Zero();
  bool has_sphere = false;       // roly-poly
  Eigen::Vector3d sphere_center = Eigen::Vector3d::Zero();
  double sphere_radius = 0.0;
  bool has_tip = false;          // spin
  Eigen::Vector3d tip = Eigen::Vector3d::Zero();
  double void_volume = -1.0;     // the report's after.void_volume; negative: compute from the shells
  // Drain holes and channels cut through the cavity (the report's openings.cut): each drawn in
  // every view as its axis and a ring of its radius at the outer end.
  struct Opening {
    Eigen::Vector3d inner = Eigen::Vector3d::Zero(), outer = Eigen::Vector3d::Zero();
    double radius = 0.0;
  };
  std::vector<Opening> openings;
};

enum class PreviewStatus { ok, bad_input };

struct PreviewResult {
  PreviewStatus status = PreviewStatus::bad_input;
  std::string message;  // why, when bad_input
  std::string svg;      // the document, when ok
};

// Draws `solid` (outer shell(s) outward, cavity shells inward, as optimize writes it). The same
// solid and input give the same bytes.
PreviewResult preview_svg(const Mesh& solid, const PreviewInput& input, const PreviewOptions& options = {});

}  // namespace offsetopt
