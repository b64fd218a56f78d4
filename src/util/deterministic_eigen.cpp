#include "util/deterministic_eigen.h"

#include <Eigen/Core>

namespace offsetopt {

void use_deterministic_eigen_blocking() {
  // Typical x86-64 sizes (32 KiB L1, 256 KiB L2, 2 MiB L3); any fixed values would do.
  Eigen::setCpuCacheSizes(32 * 1024, 256 * 1024, 2 * 1024 * 1024);
}

}  // namespace offsetopt
