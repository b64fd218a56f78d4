// The preview picture from the command line: shared by `offsetopt preview` (a result already
// written) and `optimize --preview` (the result in memory), so both draw the same SVG
// (optimize/preview_svg.h).
#pragma once
#include <string>
#include <vector>

#include "io/json.h"
#include "mesh/mesh.h"
#include "optimize/preview_svg.h"

namespace offsetopt::cli {

// Reads a PreviewInput from an optimize report (parameters, goal, before, after). Returns an
// empty string, or one line naming the missing or malformed field.
std::string preview_input_from_report(const Json& report, PreviewInput& input);

// Draws `solid` with what `report` (an optimize report) says about the goal and writes the SVG to
// `svg_path` ("-": stdout). `report_name` names the report in messages. UsageError when the report
// lacks what the picture needs or the path is one of `inputs`.
void write_preview(const std::string& svg_path, const Mesh& solid, const Json& report, const std::string& report_name,
                   const std::vector<std::string>& inputs);

}  // namespace offsetopt::cli
