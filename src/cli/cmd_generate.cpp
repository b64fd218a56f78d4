// offsetopt generate: placeholder until its issue lands; replace this file.
#include <cstdio>

#include "cli/commands.h"

namespace offsetopt::cli {

int run_generate(const Args&) {
  std::fprintf(stderr, "Error: 'generate' is not built yet\n");
  return kExitInternal;
}

}  // namespace offsetopt::cli
