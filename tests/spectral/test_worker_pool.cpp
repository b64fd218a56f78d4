// The worker pool: run() gives each thread its part; run_parts() runs a fixed number of parts,
// each exactly once, however many threads the pool has (fewer than asked when the system refuses).
#include <doctest/doctest.h>

#include <atomic>
#include <vector>

#include "spectral/worker_pool.h"

using namespace offsetopt;

TEST_CASE("worker pool: run_parts runs every part exactly once on 1, 2, 3 and 5 threads") {
  for (int threads : {1, 2, 3, 5}) {
    CAPTURE(threads);
    WorkerPool pool(threads);
    CHECK(pool.size() >= 1);
    CHECK(pool.size() <= threads);
    for (int parts : {1, 2, 4, 7}) {
      CAPTURE(parts);
      std::vector<std::atomic<int>> runs(static_cast<std::size_t>(parts));
      for (auto& r : runs) r = 0;
      for (int repeat = 0; repeat < 3; ++repeat) pool.run_parts(parts, [&](int part) { ++runs[static_cast<std::size_t>(part)]; });
      for (int p = 0; p < parts; ++p) CHECK(runs[static_cast<std::size_t>(p)] == 3);
    }
  }
}

TEST_CASE("worker pool: run gives each of its threads one part") {
  WorkerPool pool(3);
  std::vector<std::atomic<int>> runs(static_cast<std::size_t>(pool.size()));
  for (auto& r : runs) r = 0;
  pool.run([&](int part) { ++runs[static_cast<std::size_t>(part)]; });
  for (auto& r : runs) CHECK(r == 1);
}
