// offsetopt inspect: placeholder until its issue lands; replace this file.
#include <cstdio>

#include "cli/commands.h"

namespace offsetopt::cli {

int run_inspect(const Args&) {
  std::fprintf(stderr, "Error: 'inspect' is not built yet\n");
  return kExitInternal;
}

}  // namespace offsetopt::cli
