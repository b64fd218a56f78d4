// offsetopt basis: placeholder until its issue lands; replace this file.
#include <cstdio>

#include "cli/commands.h"

namespace offsetopt::cli {

int run_basis(const Args&) {
  std::fprintf(stderr, "Error: 'basis' is not built yet\n");
  return kExitInternal;
}

}  // namespace offsetopt::cli
