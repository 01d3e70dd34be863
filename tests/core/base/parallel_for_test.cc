// ParallelFor (core/base/parallel_for.h): every task once, progress in order, the first error
// rethrown and the rest skipped.
#include "core/base/parallel_for.h"

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace orbit {
namespace {

TEST(ParallelForTest, RunsEveryTaskOnceOnSeveralThreads) {
  for (int threads : {1, 2, 4}) {
    std::vector<int> runs(1000, 0);
    std::mutex mutex;
    std::set<std::thread::id> ids;
    std::vector<std::size_t> reported;
    ParallelFor(
        runs.size(), threads,
        [&](std::size_t i) {
          ++runs[i];  // each i is handed to one thread only
          std::lock_guard lock(mutex);
          ids.insert(std::this_thread::get_id());
        },
        [&](std::size_t done) { reported.push_back(done); });
    for (int r : runs) ASSERT_EQ(r, 1);
    EXPECT_LE(ids.size(), static_cast<std::size_t>(threads));
    // on_done counts 1, 2, ..., count, never concurrently.
    ASSERT_EQ(reported.size(), runs.size());
    for (std::size_t k = 0; k < reported.size(); ++k) ASSERT_EQ(reported[k], k + 1);
  }
}

TEST(ParallelForTest, NoTasksAndNoThreadsAreFine) {
  int runs = 0;
  ParallelFor(0, 4, [&](std::size_t) { ++runs; });
  EXPECT_EQ(runs, 0);
  ParallelFor(3, 0, [&](std::size_t) { ++runs; });  // threads < 1: the caller alone
  EXPECT_EQ(runs, 3);
}

TEST(ParallelForTest, RethrowsTheFirstErrorUnchangedAndSkipsTheRest) {
  std::atomic<int> started{0};
  try {
    // The other tasks take a while (10000 x 200 us = 1 s on two threads), so that the error
    // is recorded long before they could all have started, even on a loaded machine (with
    // instant tasks the other thread could run all 10 000 while the failing one waited for
    // the CPU).
    ParallelFor(10000, 2, [&](std::size_t i) {
      ++started;
      if (i == 3) throw std::out_of_range("task 3 failed");
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    });
    FAIL() << "no exception";
  } catch (const std::out_of_range& e) {
    EXPECT_STREQ(e.what(), "task 3 failed");
  }
  EXPECT_LT(started.load(), 10000);
}

TEST(ParallelForTest, AvailableCpusIsAtLeastOne) { EXPECT_GE(AvailableCpus(), 1); }

}  // namespace
}  // namespace orbit
