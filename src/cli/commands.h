// src/cli (this is the folder's main header): the command line, the top layer and the only code
// that prints: one option table per command (help and parser from the same rows), the optimize
// report written from the typed result (optimize_report.h), reading a report back for `preview`,
// and `batch`. It may include every folder; nothing includes it.
//
// The subcommands of the offsetopt binary. Each takes the arguments after its name and returns
// the process exit code (see ExitCode). Only this layer and main print.
#pragma once
#include <string>
#include <vector>

namespace offsetopt::cli {

enum ExitCode : int {
  kExitOk = 0,            // done (and, for optimize, verified)
  kExitInternal = 1,      // a bug or an unexpected failure
  kExitBadInput = 2,      // bad input or usage: one line saying what and where
  kExitGoalNotMet = 3,    // ran, but the goal is not met or the result is invalid
};

using Args = std::vector<std::string>;

int run_check(const Args& args);
int run_inspect(const Args& args);
int run_basis(const Args& args);
int run_skeleton(const Args& args);
int run_optimize(const Args& args);
int run_generate(const Args& args);
int run_preview(const Args& args);
int run_batch(const Args& args);

struct OptionSpec;
// optimize's option table (cli/cli_support.h), for batch to check a manifest's options early.
const std::vector<OptionSpec>& optimize_options();

}  // namespace offsetopt::cli
