// The worker pool (util/parallel.h): run() gives each thread its part; run_parts() runs a fixed number of parts,
// each exactly once, however many threads the pool has (fewer than asked when the system refuses).
#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <future>
#include <thread>
#include <vector>

#include "util/parallel.h"

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

TEST_CASE("worker pool: a polling pool runs every part exactly once, hand-offs caught polling or asleep") {
  // Parts that end at once (the next run is caught while the threads poll) and parts that outlast
  // the 100 µs poll (the caller and the worker sleep and are woken), alternating.
  for (PoolWait wait : {PoolWait::sleep, PoolWait::poll_then_sleep}) {
    WorkerPool pool(2, wait);
    std::vector<std::atomic<int>> runs(2);
    for (auto& r : runs) r = 0;
    std::atomic<long> sum{0};
    const int repeats = 2000;
    for (int repeat = 0; repeat < repeats; ++repeat) {
      const bool slow = repeat % 100 == 99;
      pool.run_parts(2, [&](int part) {
        ++runs[static_cast<std::size_t>(part)];
        if (slow && part == 1) std::this_thread::sleep_for(std::chrono::microseconds(300));
        sum += repeat;
      });
    }
    CHECK(runs[0] == repeats);
    CHECK(runs[1] == repeats);
    CHECK(sum == 2L * repeats * (repeats - 1) / 2);
  }
}

TEST_CASE("worker pool: run gives each of its threads one part") {
  WorkerPool pool(3);
  std::vector<std::atomic<int>> runs(static_cast<std::size_t>(pool.size()));
  for (auto& r : runs) r = 0;
  pool.run([&](int part) { ++runs[static_cast<std::size_t>(part)]; });
  for (auto& r : runs) CHECK(r == 1);
}

TEST_CASE("worker pool: run_parts_balanced runs every part exactly once, whichever thread takes it") {
  for (int threads : {1, 2, 3}) {
    CAPTURE(threads);
    WorkerPool pool(threads);
    for (int parts : {0, 1, 2, 5, 32, 100}) {
      CAPTURE(parts);
      std::vector<std::atomic<int>> runs(static_cast<std::size_t>(parts));
      for (auto& r : runs) r = 0;
      for (int repeat = 0; repeat < 3; ++repeat)
        pool.run_parts_balanced(parts, [&](int part) { ++runs[static_cast<std::size_t>(part)]; });
      for (int p = 0; p < parts; ++p) CHECK(runs[static_cast<std::size_t>(p)] == 3);
    }
  }
}

TEST_CASE("split_point: contiguous ranges from 0 to count, each ending on a granule multiple but the last") {
  for (long count : {0L, 1L, 7L, 100L, 1001L})
    for (int parts : {1, 2, 3, 8})
      for (long granule : {1L, 2L, 16L}) {
        CAPTURE(count);
        CAPTURE(parts);
        CAPTURE(granule);
        CHECK(split_point(count, parts, 0, granule) == 0);
        CHECK(split_point(count, parts, parts, granule) == count);
        for (int p = 0; p < parts; ++p) {
          const long lo = split_point(count, parts, p, granule), hi = split_point(count, parts, p + 1, granule);
          CHECK(lo <= hi);
          if (hi < count) CHECK(hi % granule == 0);
          // Sizes differ by at most one granule.
          CHECK(hi - lo <= ((count + granule - 1) / granule + parts - 1) / parts * granule);
        }
      }
}

TEST_CASE("execution_policy: parallel only with more than one thread and enough work") {
  CHECK(execution_policy(1, 1e9, 10.0) == ExecutionPolicy::serial);
  CHECK(execution_policy(2, 9.0, 10.0) == ExecutionPolicy::serial);
  CHECK(execution_policy(2, 10.0, 10.0) == ExecutionPolicy::parallel);
  CHECK(execution_policy(4, 1e9, 10.0) == ExecutionPolicy::parallel);
  CHECK(execution_policy(static_cast<const WorkerPool*>(nullptr), 1e9, 0.0) == ExecutionPolicy::serial);
  WorkerPool one(1);
  CHECK(execution_policy(&one, 1e9, 0.0) == ExecutionPolicy::serial);
  WorkerPool two(2);
  if (two.size() == 2) {
    CHECK(execution_policy(&two, 16.0, 16.0) == ExecutionPolicy::parallel);
    CHECK(execution_policy(&two, 15.0, 16.0) == ExecutionPolicy::serial);
  }
}

TEST_CASE("for_ranges: every index exactly once, in ranges of at least per_thread, serial below two ranges") {
  for (long count : {0L, 1L, 99L, 100L, 199L, 200L, 1001L}) {
    for (int threads : {1, 2, 3, 8}) {
      CAPTURE(count);
      CAPTURE(threads);
      std::vector<std::atomic<int>> seen(static_cast<std::size_t>(count));
      for (auto& s : seen) s = 0;
      std::atomic<int> ranges{0};
      std::atomic<long> shortest{count};
      for_ranges(count, threads, 100, [&](long begin, long end) {
        ++ranges;
        long expected = shortest.load();
        while (end - begin < expected && !shortest.compare_exchange_weak(expected, end - begin)) {
        }
        for (long i = begin; i < end; ++i) ++seen[static_cast<std::size_t>(i)];
      });
      for (auto& s : seen) CHECK(s == 1);
      // Expected ranges: one unless two or more threads and at least two ranges' worth of items.
      const long wanted = threads > 1 && count >= 200 ? std::min<long>(threads, count / 100) : 1;
      CHECK(ranges <= wanted);  // the system may give fewer threads
      CHECK(ranges >= 1);
      if (ranges > 1) CHECK(shortest >= 100);
    }
  }
}

TEST_CASE("start_task: the same result run alongside or deferred") {
  int calls = 0;
  auto work = [&calls] { return ++calls * 7; };
  std::future<int> deferred = start_task(false, work);
  CHECK(calls == 0);  // not run until asked for
  CHECK(deferred.get() == 7);
  std::future<int> alongside = start_task(true, work);
  CHECK(alongside.get() == 14);
  CHECK(calls == 2);
}
