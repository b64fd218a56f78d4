// Eigen splits long dense products into blocks sized from the CPU's cache sizes, read at run
// time; a different blocking sums in a different order, so the same binary could round
// differently on another machine. Fixing the cache sizes Eigen plans with makes the blocking, and
// so every dense product, the same everywhere. Call once at start-up, before any computation.
#pragma once

namespace offsetopt {

void use_deterministic_eigen_blocking();

}  // namespace offsetopt
