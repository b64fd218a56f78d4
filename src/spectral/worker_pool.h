// A fixed set of threads for the eigensolver's data-parallel loops. Work is always split into
// the same parts, each part writes outputs no other part touches, and every sum stays inside one
// part in the order the single-threaded code uses, so results are bit for bit the same for any
// number of threads (DESIGN.md: threads only with a fixed partition and fixed reduction order).
#pragma once
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace offsetopt {

class WorkerPool {
 public:
  // `threads` >= 1 in total, the calling thread included; fewer when the system refuses to start
  // more (see size()).
  explicit WorkerPool(int threads);
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

 private:
  void work(int part);

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable start_, done_;
  const std::function<void(int)>* task_ = nullptr;
  unsigned long generation_ = 0;
  int pending_ = 0;
  bool stop_ = false;
};

// Splits [0, count) into `parts` contiguous ranges, sizes differing by at most `granule`
// multiples: range p is [split_point(p), split_point(p + 1)).
inline long split_point(long count, int parts, int p, long granule = 1) {
  const long units = (count + granule - 1) / granule;
  const long point = units * p / parts * granule;
  return point < count ? point : count;
}

}  // namespace offsetopt
