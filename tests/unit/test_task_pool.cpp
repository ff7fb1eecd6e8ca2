// lgh::TaskPool (lgh/task_pool.hpp): its workers sleep on a counting semaphore, one count per
// queued task and one per worker at stop.
//  - every task submitted runs once, from many submitting threads at a time;
//  - the pool's end runs what is still queued, and ends every worker;
//  - parallelFor runs every index once, with and without idle workers to help, and rethrows;
//  - waitIdle returns once nothing is queued or running;
//  - submitting never waits for a worker (held workers would make such a test hang).
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include "lgh/task_pool.hpp"

namespace lgh {
namespace {

TEST(TaskPool, EveryTaskSubmittedFromManyThreadsRunsOnce) {
  constexpr std::size_t kSubmitters = 4;
  constexpr std::size_t kTasksEach = 5000;
  std::vector<std::atomic<int>> runs(kSubmitters * kTasksEach);
  TaskPool pool(8, "lgh-test");
  std::vector<std::thread> submitters;
  for (std::size_t s = 0; s < kSubmitters; ++s) {
    submitters.emplace_back([&, s] {
      for (std::size_t i = 0; i < kTasksEach; ++i) {
        pool.submit([&runs, index = s * kTasksEach + i] { runs[index].fetch_add(1); });
      }
    });
  }
  for (std::thread& submitter : submitters) submitter.join();
  pool.waitIdle();
  for (std::size_t i = 0; i < runs.size(); ++i) ASSERT_EQ(runs[i].load(), 1) << "task " << i;
  EXPECT_EQ(pool.idleWorkers(), 8);
}

TEST(TaskPool, ItsEndRunsWhatIsStillQueued) {
  std::atomic<int> ran{0};
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::thread releaser;
  {
    TaskPool pool(2, "lgh-test");
    // Both workers held, so that the rest waits in the queue when the pool ends.
    for (int i = 0; i < 2; ++i) {
      pool.submit([released, &ran] {
        released.wait();
        ++ran;
      });
    }
    for (int i = 0; i < 100; ++i) pool.submit([&ran] { ++ran; });
    releaser = std::thread([&release] {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      release.set_value();
    });
  }  // ~TaskPool: runs the queue once the workers are let go, then joins them
  releaser.join();
  EXPECT_EQ(ran.load(), 102);
}

TEST(TaskPool, AnIdlePoolEndsEveryWorker) {
  for (int round = 0; round < 50; ++round) {
    TaskPool pool(16, "lgh-test");
    EXPECT_EQ(pool.threads(), 16);
  }  // each ~TaskPool joins its sixteen workers, or the test hangs
}

TEST(TaskPool, ParallelForRunsEveryIndexOnceWithOrWithoutHelpers) {
  TaskPool pool(4, "lgh-test");
  for (const int count : {1, 3, 1000}) {
    std::vector<std::atomic<int>> runs(static_cast<std::size_t>(count));
    pool.parallelFor(static_cast<std::size_t>(count), [&](std::size_t i) { runs[i].fetch_add(1); });
    for (const auto& run : runs) ASSERT_EQ(run.load(), 1) << count << " indices";
  }
  // Every worker busy: the caller runs every index itself.
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  for (int i = 0; i < 4; ++i) pool.submit([released] { released.wait(); });
  std::atomic<int> done{0};
  std::set<std::thread::id> threads;
  std::mutex mutex;
  pool.parallelFor(50, [&](std::size_t) {
    ++done;
    const std::lock_guard lock(mutex);
    threads.insert(std::this_thread::get_id());
  });
  EXPECT_EQ(done.load(), 50);
  EXPECT_EQ(threads, std::set<std::thread::id>{std::this_thread::get_id()});
  release.set_value();
  pool.waitIdle();
}

TEST(TaskPool, ParallelForRethrowsTheFirstError) {
  TaskPool pool(4, "lgh-test");
  std::atomic<int> ran{0};
  EXPECT_THROW(pool.parallelFor(100,
                                [&](std::size_t i) {
                                  ++ran;
                                  if (i == 7) throw std::runtime_error("index 7");
                                }),
               std::runtime_error);
  EXPECT_EQ(ran.load(), 100) << "the other indices still run";
  pool.waitIdle();
}

TEST(TaskPool, SubmittingDoesNotWaitForBusyWorkers) {
  TaskPool pool(2, "lgh-test");
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::atomic<int> ran{0};
  for (int i = 0; i < 2; ++i) {
    pool.submit([released, &ran] {
      released.wait();
      ++ran;
    });
  }
  for (int i = 0; i < 10000; ++i) pool.submit([&ran] { ++ran; });  // every worker held
  EXPECT_EQ(ran.load(), 0);
  EXPECT_EQ(pool.idleWorkers(), 0);
  release.set_value();
  pool.waitIdle();
  EXPECT_EQ(ran.load(), 10002);
}

}  // namespace
}  // namespace lgh
