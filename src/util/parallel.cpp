#include "util/parallel.h"

#include <chrono>
#include <system_error>

namespace offsetopt {

WorkerPool::WorkerPool(int threads, PoolWait wait)
    : poll_(wait == PoolWait::poll_then_sleep ? std::chrono::microseconds(100) : std::chrono::nanoseconds(0)) {
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

namespace {

inline void spin_pause() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}

// True as soon as ready() is, polling for at most `budget` (none: a single test). A pause costs
// 10 to 140 cycles depending on the processor, so the budget is read off the clock.
template <typename Ready>
bool poll_until(std::chrono::nanoseconds budget, const Ready& ready) {
  if (budget.count() <= 0) return ready();
  const auto until = std::chrono::steady_clock::now() + budget;
  while (true) {
    for (int i = 0; i < 16; ++i) {
      if (ready()) return true;
      spin_pause();
    }
    if (std::chrono::steady_clock::now() >= until) return ready();
  }
}

}  // namespace

void WorkerPool::run(const std::function<void(int)>& task) {
  if (workers_.empty()) {
    task(0);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    task_.store(&task, std::memory_order_relaxed);
    pending_.store(static_cast<int>(workers_.size()), std::memory_order_relaxed);
    generation_.fetch_add(1, std::memory_order_release);
  }
  start_.notify_all();
  task(0);
  if (!poll_until(poll_, [this] { return pending_.load(std::memory_order_acquire) == 0; })) {
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [this] { return pending_.load(std::memory_order_acquire) == 0; });
  }
  task_.store(nullptr, std::memory_order_relaxed);
}

void WorkerPool::run_parts(int parts, const std::function<void(int)>& task) {
  const int threads = size();
  run([&](int thread) {
    for (int part = thread; part < parts; part += threads) task(part);
  });
}

void WorkerPool::run_parts_balanced(int parts, const std::function<void(int)>& task) {
  std::atomic<int> next{0};
  run([&](int) {
    for (int part = next.fetch_add(1); part < parts; part = next.fetch_add(1)) task(part);
  });
}

void WorkerPool::work(int part) {
  unsigned long seen = 0;
  while (true) {
    if (!poll_until(poll_, [&] { return generation_.load(std::memory_order_acquire) != seen; })) {
      std::unique_lock<std::mutex> lock(mutex_);
      start_.wait(lock, [&] { return stop_ || generation_.load(std::memory_order_acquire) != seen; });
      if (stop_) return;
    }
    seen = generation_.load(std::memory_order_acquire);
    const std::function<void(int)>* task = task_.load(std::memory_order_relaxed);
    (*task)(part);
    if (pending_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
      // The caller may be asleep: wake it under the lock, so the wake cannot fall between its
      // test of pending_ and its wait.
      std::lock_guard<std::mutex> lock(mutex_);
      done_.notify_one();
    }
  }
}

}  // namespace offsetopt
