// offsetopt skeleton: placeholder until its issue lands; replace this file.
#include <cstdio>

#include "cli/commands.h"

namespace offsetopt::cli {

int run_skeleton(const Args&) {
  std::fprintf(stderr, "Error: 'skeleton' is not built yet\n");
  return kExitInternal;
}

}  // namespace offsetopt::cli
