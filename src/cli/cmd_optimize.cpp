// offsetopt optimize: placeholder until its issue lands; replace this file.
#include <cstdio>

#include "cli/commands.h"

namespace offsetopt::cli {

int run_optimize(const Args&) {
  std::fprintf(stderr, "Error: 'optimize' is not built yet\n");
  return kExitInternal;
}

}  // namespace offsetopt::cli
