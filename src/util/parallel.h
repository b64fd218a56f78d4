// src/util: the lowest layer, beside src/optim. It owns what every other folder may use and that
// knows nothing of meshes: deterministic maths (det_math), error-free expansions, dual numbers,
// shortest round-trip number text, the project's RNG, and this file's thread pool and
// serial-or-parallel policy. It includes only the standard library, Eigen and itself.
//
// Threads with a fixed partition and a fixed reduction order (docs/design.md): work is always split
// into the same parts, each part writes outputs no other part touches, and every sum stays inside
// one part in the order the single-threaded code uses, so results are bit for bit the same for
// any number of threads. Used by the eigensolver, the sparse factorisations, the offset field,
// the reduced problem, verification, grid winding numbers and the contoured cavity. Every thread
// the program starts comes from here (WorkerPool, start_task).
//
// The size policy (after Manifold's autoPolicy, Manifold/src/parallel.h): whether a loop is worth
// waking the pool for is decided by one function, execution_policy(), from the work's size and
// the call site's threshold (in the call site's own unit: panels, rows, multiply-adds). Because
// of the fixed partition, the decision only changes speed, never a result.
#pragma once
#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <future>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace offsetopt {

// How an idle thread of a pool waits for its next task, and the caller for the last part's end.
// Woken from sleep, a thread here takes tens of microseconds to run again, about as long as one
// part of a reduced-problem evaluation at 10^3 to 10^4 vertices (three hand-offs each): the
// correction's solve of stand-filled --outer took 0.15 s sleeping, 0.13 s polling for 100 µs
// first, 0.15 s polling for 10 µs (5 runs each, two threads). Polling takes the core from any other
// task, so only a pool of such short parts that runs alone asks for it: with every pool polling,
// the sphere's front (three tasks on two cores) took longer.
enum class PoolWait { sleep, poll_then_sleep };

class WorkerPool {
 public:
  // `threads` >= 1 in total, the calling thread included; fewer when the system refuses to start
  // more (see size()). poll_then_sleep polls for 100 µs before sleeping.
  explicit WorkerPool(int threads, PoolWait wait = PoolWait::sleep);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  int size() const { return static_cast<int>(workers_.size()) + 1; }
  // Runs task(part) for every part in [0, size()), part 0 on the calling thread; returns when
  // all are done. Tasks must not throw.
  void run(const std::function<void(int)>& task);
  // Runs task(p) once for every p in [0, parts), part p on thread p mod size(); returns when all
  // are done. For work cut into a fixed number of parts, which must all run even when the pool
  // got fewer threads than asked for. Tasks must not throw.
  void run_parts(int parts, const std::function<void(int)>& task);
  // Runs task(p) once for every p in [0, parts), each part on whichever thread is free next. For
  // parts whose cost varies (regions of a mesh) and whose outputs do not depend on the thread
  // that ran them: then the result is run_parts' and the threads finish together. Tasks must not
  // throw.
  void run_parts_balanced(int parts, const std::function<void(int)>& task);

 private:
  void work(int part);

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable start_, done_;
  // Written under mutex_ and read without it while a thread spins before it sleeps (work, run).
  std::atomic<const std::function<void(int)>*> task_{nullptr};
  std::atomic<unsigned long> generation_{0};
  std::atomic<int> pending_{0};
  bool stop_ = false;
  const std::chrono::nanoseconds poll_;  // how long a thread polls before it sleeps
};

// Splits [0, count) into `parts` contiguous ranges, sizes differing by at most `granule`
// multiples: range p is [split_point(p), split_point(p + 1)).
inline long split_point(long count, int parts, int p, long granule = 1) {
  const long units = (count + granule - 1) / granule;
  const long point = units * p / parts * granule;
  return point < count ? point : count;
}

enum class ExecutionPolicy { serial, parallel };

// parallel when there is more than one thread to run on (`threads`: the pool's size, or the
// threads a caller was given) and `work` is at least `min_parallel_work`, both in the caller's
// unit; serial otherwise.
inline ExecutionPolicy execution_policy(int threads, double work, double min_parallel_work) {
  return threads > 1 && work >= min_parallel_work ? ExecutionPolicy::parallel : ExecutionPolicy::serial;
}

// The same for a pool that may be absent (nullptr: serial).
inline ExecutionPolicy execution_policy(const WorkerPool* pool, double work, double min_parallel_work) {
  return execution_policy(pool ? pool->size() : 1, work, min_parallel_work);
}

// body(begin, end) over [0, count) cut into contiguous ranges, one per thread: as many threads as
// `threads` allows with at least `per_thread` items each, and serial below two such ranges (a
// thread costs more than it saves on less). body must write only its own range's outputs; then
// the count changes no result.
template <typename Body>
void for_ranges(long count, int threads, long per_thread, const Body& body) {
  const int used = execution_policy(threads, static_cast<double>(count), 2.0 * static_cast<double>(per_thread)) ==
                           ExecutionPolicy::parallel
                       ? static_cast<int>(std::min<long>(threads, count / per_thread))
                       : 1;
  WorkerPool pool(used);
  pool.run([&](int part) { body(split_point(count, pool.size(), part), split_point(count, pool.size(), part + 1)); });
}

// `work()` started on a thread of its own when `alongside` and the system gives one, else run on
// the first thread that asks the future for its result: the same result either way. For a stage
// the calling thread does not wait for at once (optimize_offsets' basis and skeleton run
// alongside its reachability programme); work cut into parts uses WorkerPool.
template <class Work>
std::future<decltype(std::declval<Work&>()())> start_task(bool alongside, Work work) {
  if (alongside) {
    try {
      return std::async(std::launch::async, work);
    } catch (const std::system_error&) {  // no thread to be had: computed when asked for
    }
  }
  return std::async(std::launch::deferred, std::move(work));
}

}  // namespace offsetopt
