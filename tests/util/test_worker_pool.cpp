// WorkerPool (util/parallel_for.h): every task runs exactly once, on a valid worker; the first
// exception reaches the caller and stops the loop; one pool serves many loops, tiny and large,
// with and without time for its threads to fall asleep in between; 1 and 2 workers, and more
// workers than hardware threads.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include "coxmesh/util/parallel_for.h"

using coxmesh::WorkerPool;

namespace {

// Runs one loop of `tasks` tasks and checks that each ran once, on a worker of the pool.
void expect_each_task_once(WorkerPool& pool, std::size_t tasks) {
  std::vector<std::atomic<int>> runs(tasks);
  std::atomic<int> bad_worker{0};
  pool.run(tasks, [&](std::size_t t, int worker) {
    runs[t].fetch_add(1, std::memory_order_relaxed);
    if (worker < 0 || worker >= pool.size()) bad_worker.fetch_add(1);
  });
  for (std::size_t t = 0; t < tasks; ++t) ASSERT_EQ(runs[t].load(), 1) << "task " << t << " of " << tasks;
  EXPECT_EQ(bad_worker.load(), 0);
}

}  // namespace

TEST(WorkerPool, EveryTaskRunsExactlyOnce) {
  for (int workers : {1, 2, 3, 8}) {
    SCOPED_TRACE(workers);
    WorkerPool pool(workers);
    EXPECT_EQ(pool.size(), workers);
    for (std::size_t tasks : {0, 1, 2, 3, 7, 100, 10000}) expect_each_task_once(pool, tasks);
  }
  WorkerPool none(0);  // at least one worker: the caller
  EXPECT_EQ(none.size(), 1);
  expect_each_task_once(none, 5);
}

TEST(WorkerPool, OneWorkerRunsTheTasksInOrderOnTheCaller) {
  WorkerPool pool(1);
  const auto caller = std::this_thread::get_id();
  std::vector<std::size_t> order;
  bool elsewhere = false;
  pool.run(50, [&](std::size_t t, int worker) {
    order.push_back(t);
    elsewhere |= worker != 0 || std::this_thread::get_id() != caller;
  });
  ASSERT_EQ(order.size(), 50u);
  for (std::size_t t = 0; t < order.size(); ++t) EXPECT_EQ(order[t], t);
  EXPECT_FALSE(elsewhere);
}

TEST(WorkerPool, TwoWorkersBothTakeTasks) {
  // The caller blocks in its first task until the other worker has taken one: fails (by timing
  // out) if the pool ran everything on the caller.
  WorkerPool pool(2);
  std::atomic<bool> second_worker_ran{false};
  pool.run(2, [&](std::size_t, int worker) {
    if (worker == 1) {
      second_worker_ran = true;
      return;
    }
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (!second_worker_ran && std::chrono::steady_clock::now() < deadline) std::this_thread::yield();
  });
  EXPECT_TRUE(second_worker_ran);
}

TEST(WorkerPool, ReusedAcrossManyLoopsAwakeAndAsleep) {
  WorkerPool pool(2);
  std::size_t total = 0;
  for (int loop = 0; loop < 300; ++loop) {
    const std::size_t tasks = loop % 7 == 0 ? 1000 : static_cast<std::size_t>(loop % 5);
    std::atomic<std::size_t> sum{0};
    pool.run(tasks, [&](std::size_t t, int) { sum.fetch_add(t + 1); });
    ASSERT_EQ(sum.load(), tasks * (tasks + 1) / 2) << "loop " << loop;
    total += tasks;
    // Every 50 loops, long enough for the workers to stop spinning and sleep.
    if (loop % 50 == 49) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  EXPECT_GT(total, 0u);
}

TEST(WorkerPool, TheFirstExceptionReachesTheCallerAndThePoolStaysUsable) {
  for (int workers : {1, 2}) {
    SCOPED_TRACE(workers);
    WorkerPool pool(workers);
    std::atomic<int> ran{0};
    try {
      pool.run(10000, [&](std::size_t t, int) {
        ran.fetch_add(1);
        if (t == 10) throw std::runtime_error("task 10");
        std::this_thread::sleep_for(std::chrono::microseconds(200));
      });
      ADD_FAILURE() << "no exception";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "task 10");
    }
    // No task starts once the failure is seen: a handful ran after task 10, not the 9989 others
    // (2 s of tasks; this fails only if the thrower stalls for 0.2 s).
    EXPECT_LT(ran.load(), 1000);
    // Only one of several exceptions arrives, and the pool still runs every task of the next loop.
    EXPECT_THROW(pool.run(100, [](std::size_t, int) { throw std::logic_error("every task"); }), std::logic_error);
    expect_each_task_once(pool, 1000);
  }
}

TEST(WorkerPool, ResolveThreads) {
  EXPECT_EQ(coxmesh::resolve_threads(3), 3);
  EXPECT_GE(coxmesh::resolve_threads(0), 1);
}
