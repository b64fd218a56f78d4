// offsetopt check: placeholder until its issue lands; replace this file.
#include <cstdio>

#include "cli/commands.h"

namespace offsetopt::cli {

int run_check(const Args&) {
  std::fprintf(stderr, "Error: 'check' is not built yet\n");
  return kExitInternal;
}

}  // namespace offsetopt::cli
