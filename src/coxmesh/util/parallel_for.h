// Fork–join over numbered tasks. Results must not depend on which worker ran which task: callers
// write task t's output to slot t and merge the slots in task order (deterministic output).
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace coxmesh {

/// Number of workers to use for `requested` (0 = all hardware threads).
inline int resolve_threads(int requested) {
  if (requested > 0) return requested;
  return std::max(1u, std::thread::hardware_concurrency());
}

/// A fixed set of workers for many short parallel loops (one per breadth-first level, one per batch
/// of cells): the threads are started once, not per loop. The calling thread is worker 0.
/// Between loops a worker spins for a short while before it sleeps, and so does the caller while
/// it waits for the workers: loops come every few hundred microseconds (between them the caller
/// merges), and waking a sleeping thread costs a good part of that (docs/benchmarks.md).
/// With more workers than hardware threads nobody spins: a spinning thread would hold a core that
/// a working one needs.
class WorkerPool {
 public:
  explicit WorkerPool(int workers)
      : workers_(std::max(workers, 1)),
        spin_(workers_ <= static_cast<int>(std::thread::hardware_concurrency()) ? std::chrono::microseconds(200)
                                                                                : std::chrono::microseconds(0)) {
    for (int w = 1; w < workers_; ++w) threads_.emplace_back([this, w] { serve(w); });
  }
  ~WorkerPool() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
      generation_.fetch_add(1);
    }
    wake_.notify_all();
    for (auto& t : threads_) t.join();
  }
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  int size() const { return workers_; }

  /// Runs fn(task, worker) for every task in [0, tasks), handed out dynamically in increasing
  /// order. The first exception thrown by a task is rethrown here once every worker has stopped.
  void run(std::size_t tasks, const std::function<void(std::size_t, int)>& fn) {
    if (workers_ == 1 || tasks <= 1) {  // not worth waking anyone
      for (std::size_t t = 0; t < tasks; ++t) fn(t, 0);
      return;
    }
    fn_ = &fn;  // (published to the workers by the generation's increment)
    tasks_ = tasks;
    next_.store(0, std::memory_order_relaxed);
    failed_.store(false, std::memory_order_relaxed);
    error_ = nullptr;
    busy_.store(workers_ - 1, std::memory_order_relaxed);
    generation_.fetch_add(1);  // seq_cst, against sleepers_ (see serve)
    if (sleepers_.load() > 0) {
      std::lock_guard<std::mutex> lock(mutex_);
      wake_.notify_all();
    }
    work(0);
    if (!spin_until([this] { return busy_.load(std::memory_order_acquire) == 0; })) {
      std::unique_lock<std::mutex> lock(mutex_);
      caller_sleeps_.store(true);
      done_.wait(lock, [this] { return busy_.load() == 0; });
      caller_sleeps_.store(false);
    }
    fn_ = nullptr;
    if (error_) std::rethrow_exception(error_);
  }

 private:
  template <class Ready>
  bool spin_until(Ready&& ready) const {
    const auto start = std::chrono::steady_clock::now();
    for (int i = 1;; ++i) {
      if (ready()) return true;
#if defined(__x86_64__) || defined(__i386__)
      __builtin_ia32_pause();
#endif
      if (i % 64 == 0 && std::chrono::steady_clock::now() - start > spin_) return false;
    }
  }
  void work(int worker) {
    for (std::size_t t; !failed_.load(std::memory_order_relaxed) && (t = next_.fetch_add(1)) < tasks_;) {
      try {
        (*fn_)(t, worker);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!error_) error_ = std::current_exception();
        failed_ = true;
      }
    }
  }
  void serve(int worker) {
    std::uint64_t seen = 0;
    for (;;) {
      if (!spin_until([&] { return generation_.load(std::memory_order_acquire) != seen; })) {
        std::unique_lock<std::mutex> lock(mutex_);
        sleepers_.fetch_add(1);  // seq_cst: run() either sees a sleeper or we see its generation
        wake_.wait(lock, [&] { return generation_.load() != seen; });
        sleepers_.fetch_sub(1);
      }
      seen = generation_.load(std::memory_order_acquire);
      if (stopping_.load()) return;
      work(worker);
      if (busy_.fetch_sub(1) == 1 && caller_sleeps_.load()) {  // the last one out wakes the caller
        std::lock_guard<std::mutex> lock(mutex_);
        done_.notify_one();
      }
    }
  }

  const int workers_;
  const std::chrono::microseconds spin_;  // how long a waiting thread spins before it sleeps
  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  const std::function<void(std::size_t, int)>* fn_ = nullptr;
  std::size_t tasks_ = 0;
  std::atomic<std::size_t> next_{0};
  std::atomic<bool> failed_{false};
  std::exception_ptr error_;
  std::atomic<int> busy_{0}, sleepers_{0};
  std::atomic<bool> caller_sleeps_{false}, stopping_{false};
  std::atomic<std::uint64_t> generation_{0};
};

}  // namespace coxmesh
