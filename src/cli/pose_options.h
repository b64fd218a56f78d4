// The pose options `inspect` and `optimize` share (issue 13; docs/design.md "Command line"):
// --up AXIS (an exact signed permutation to z up), --pose as-is|stable (rest on the most stable
// convex-hull facet) and --flatten H (cut a flat base H above the lowest point), applied in that
// order to the loaded mesh, and the "pose" object of the reports.
#pragma once
#include <string>
#include <vector>

#include "cli/cli_support.h"
#include "geometry/pose.h"
#include "io/json.h"
#include "mesh/mesh.h"

namespace offsetopt::cli {

struct PoseOptions {
  std::string up = "+z";
  bool stable = false;
  double flatten = 0.0;  // 0: no cut
  bool any() const { return up != "+z" || stable || flatten > 0.0; }
  // Empty when the options are valid (an up axis up_axis_permutation knows, a flatten height that
  // is 0 or positive and finite), else what is wrong.
  std::string check() const;
};

// The three options' rows for the commands' option tables (help and parser, cli_support.h);
// constant-initialised, so other tables may copy them at start-up.
inline constexpr OptionSpec kPoseOptionSpecs[3] = {
    {"--up", "AXIS", "+z", "+x | -x | +y | -y | +z | -z",
     "the input's up axis; the mesh is turned exactly (a signed permutation of the axes) to z up, and every output mesh "
     "is turned back to the input's frame",
     "+y"},
    {"--pose", "MODE", "as-is", "as-is | stable",
     "stable: rest on the convex-hull face that keeps the centre of mass furthest inside it, lowest point at z = 0; "
     "outputs are then written in that new pose",
     "stable"},
    {"--flatten", "H", "none", OptionRange::real_above(0, 1e12, " mesh units"),
     "cut a flat base H above the lowest point and cap it, after --up and --pose (for objects touching the ground in a "
     "point or a line); figures are of the result, in the turned frame (the report's \"pose\" object gives the rotation "
     "and what was done)",
     "0.5"},
};

// When `arg` is --up, --pose or --flatten: reads its value into `options` and returns true.
bool parse_pose_option(const std::string& arg, ArgCursor& cursor, PoseOptions& options);

struct PosedInput {
  Mesh mesh;                  // the working mesh: z up, posed, flattened
  AxisPermutation up;         // applied first
  bool outputs_in_input_frame = true;  // false once the pose was changed on purpose
  Json report = Json::object();        // the reports' "pose" object
  std::vector<std::string> warnings;
};

// Applies the options to `mesh` (as loaded from `mesh_path`). A cut that leaves no valid solid,
// or (with single_component) several pieces, is a UsageError naming the file.
PosedInput pose_input(const Mesh& mesh, const PoseOptions& options, const std::string& mesh_path, bool single_component);

// A mesh of the working frame in the frame outputs are written in (the input's, unless posed).
Mesh to_output_frame(const Mesh& mesh, const PosedInput& posed);

}  // namespace offsetopt::cli
