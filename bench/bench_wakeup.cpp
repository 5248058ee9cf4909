// The cost of waking a WorkerPool's sleeping thread: the time of a loop of two empty tasks when the
// second worker has slept (the caller waited longer than the pool's spin), against the same loop
// right after another, while the worker still spins. Why the pool spins between loops
// (util/parallel_for.h; docs/benchmarks.md).
//
// Usage: bench_wakeup [loops = 1000]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>
#include <vector>

#include "coxmesh/util/parallel_for.h"

int main(int argc, char** argv) {
  using Clock = std::chrono::steady_clock;
  const int loops = argc > 1 ? std::max(10, std::atoi(argv[1])) : 1000;
  coxmesh::WorkerPool pool(2);
  const auto timed_loop = [&] {
    const auto start = Clock::now();
    pool.run(2, [](std::size_t, int) {});
    return std::chrono::duration<double, std::micro>(Clock::now() - start).count();
  };
  std::vector<double> asleep, spinning;
  for (int i = 0; i < loops; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));  // (the pool spins 200 µs)
    asleep.push_back(timed_loop());
    spinning.push_back(timed_loop());
  }
  const auto quantile = [](std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
  };
  std::printf(
      "loop of 2 empty tasks, %d times (µs): worker asleep: median %.1f (p10 %.1f, p90 %.1f); "
      "worker spinning: median %.1f (p10 %.1f, p90 %.1f)\n",
      loops, quantile(asleep, 0.5), quantile(asleep, 0.1), quantile(asleep, 0.9), quantile(spinning, 0.5),
      quantile(spinning, 0.1), quantile(spinning, 0.9));
}
