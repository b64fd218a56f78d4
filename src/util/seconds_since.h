// Wall-clock seconds since a start time: the stage timings of progress lines and reports (never
// an input to a result, so determinism is not at stake).
#pragma once
#include <chrono>

namespace offsetopt {

inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace offsetopt
