// The JSON report of `offsetopt optimize` (README "The report"), written from the typed result of
// optimize/offset_optimization.h: the library returns values, the command line chooses the keys,
// their order and the text (io/json.h, numbers by util/format_double).
#pragma once
#include "io/json.h"
#include "optimize/offset_optimization.h"

namespace offsetopt::cli {

// The keys a run contributes, in the report's order: parameters (the options with the lengths
// they resolved to), goal, frame, offset_field, basis, solver, before, cavity, after, goal_met,
// valid and, when the goal is not met, why. `options` are those `result` was computed with.
// The command adds input, format, vertices, faces and pose before them and outputs and timings
// after.
Json optimize_report(const OptimizeOptions& options, const OptimizeResult& result);

// The report's "after" object: the goal's figures, then the validity figures, the verdicts and
// the failures.
Json verification_json(const Verification& verification);

// The report's "timings" object without the command's own load and write stages.
Json stage_timings_json(const StageTimings& timings);

}  // namespace offsetopt::cli
