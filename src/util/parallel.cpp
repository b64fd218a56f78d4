#include "util/parallel.h"

#include <system_error>

namespace offsetopt {

WorkerPool::WorkerPool(int threads) {
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
    pending_ = static_cast<int>(workers_.size());
    ++generation_;
  }
  start_.notify_all();
  task(0);
  std::unique_lock<std::mutex> lock(mutex_);
  done_.wait(lock, [this] { return pending_ == 0; });
  task_ = nullptr;
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
    const std::function<void(int)>* task;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      start_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
      task = task_;
    }
    (*task)(part);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (--pending_ == 0) done_.notify_one();
    }
  }
}

}  // namespace offsetopt
