// The one doctest main shared by every test executable: the same fixed Eigen blocking as the
// binary (util/deterministic_eigen.h), then doctest.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include "util/deterministic_eigen.h"

int main(int argc, char** argv) {
  offsetopt::use_deterministic_eigen_blocking();
  return doctest::Context(argc, argv).run();
}
