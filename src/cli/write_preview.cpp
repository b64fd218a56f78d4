// See write_preview.h.
#include "cli/write_preview.h"

#include "cli/cli_support.h"
#include "shape/preview_svg.h"

namespace offsetopt::cli {

void write_preview(const std::string& svg_path, const Mesh& solid, const Json& report, const std::string& report_name,
                   const std::vector<std::string>& inputs) {
  PreviewInput input;
  if (const std::string problem = preview_input_from_report(report, input); !problem.empty())
    throw UsageError(problem + ", " + report_name);
  const PreviewResult picture = preview_svg(solid, input);
  if (picture.status != PreviewStatus::ok) throw UsageError("cannot draw the preview: " + picture.message);
  write_text(svg_path, picture.svg, inputs);
}

}  // namespace offsetopt::cli
