#include "util/parallel.h"

#include <system_error>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace offsetopt {
namespace {

void pause() {
#if defined(__SSE2__)
  _mm_pause();
#endif
}

}  // namespace

WorkerPool::WorkerPool(int threads, int spin) : spin_(std::max(spin, 0)) {
  try {
    for (int part = 1; part < threads; ++part) workers_.emplace_back([this, part] { work(part); });
  } catch (const std::system_error&) {
    // No more threads to be had: the pool runs with those it got (size() says how many), which
    // changes no result.
  }
}

WorkerPool::~WorkerPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  start_.notify_all();
  for (auto& worker : workers_) worker.join();
}

void WorkerPool::run(const std::function<void(int)>& task) {
  if (workers_.empty()) {
    task(0);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    task_ = &task;
    pending_.store(static_cast<int>(workers_.size()));
    generation_.fetch_add(1);
  }
  start_.notify_all();
  task(0);
  for (int spin = 0; spin < spin_ && pending_.load() != 0; ++spin) pause();
  std::unique_lock<std::mutex> lock(mutex_);
  done_.wait(lock, [this] { return pending_.load() == 0; });
  task_ = nullptr;
}

void WorkerPool::run_parts(int parts, const std::function<void(int)>& task) {
  const int threads = size();
  run([&](int thread) {
    for (int part = thread; part < parts; part += threads) task(part);
  });
}

void PhaseBarrier::arrive_and_wait() {
  const unsigned long phase = phase_.load();
  if (arrived_.fetch_add(1) + 1 == threads_) {
    arrived_.store(0);  // before the phase moves on: a thread released may arrive again at once
    {
      std::lock_guard<std::mutex> lock(mutex_);
      phase_.fetch_add(1);
    }
    next_.notify_all();
    return;
  }
  for (int spin = 0; spin < spin_ && phase_.load() == phase; ++spin) pause();
  std::unique_lock<std::mutex> lock(mutex_);
  next_.wait(lock, [&] { return phase_.load() != phase; });
}

void WorkerPool::work(int part) {
  unsigned long seen = 0;
  while (true) {
    const std::function<void(int)>* task;
    for (int spin = 0; spin < spin_ && generation_.load() == seen; ++spin) pause();
    {
      std::unique_lock<std::mutex> lock(mutex_);
      start_.wait(lock, [&] { return stop_ || generation_.load() != seen; });
      if (stop_) return;
      seen = generation_.load();
      task = task_;
    }
    (*task)(part);
    // The caller waits under the mutex for the count to reach 0: it is lowered first, then the
    // mutex is taken to notify, so the caller either sees 0 or is already waiting.
    if (pending_.fetch_sub(1) == 1) {
      std::lock_guard<std::mutex> lock(mutex_);
      done_.notify_one();
    }
  }
}

}  // namespace offsetopt
