// WorkerPool (server/worker_pool.h): tasks run in arrival order, all of them before the pool is
// gone, and the bulk pool's threads run at the niceness they were given.
#include "server/worker_pool.h"

#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <mutex>
#include <vector>

#include <gtest/gtest.h>

namespace orbit::server {
namespace {

TEST(WorkerPoolTest, OneThreadRunsTasksInArrivalOrderAndAllBeforeTheDestructorReturns) {
  std::vector<int> order;
  {
    WorkerPool pool(1);
    for (int i = 0; i < 100; ++i) pool.Post([&order, i] { order.push_back(i); });
  }
  ASSERT_EQ(order.size(), 100u);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(order[i], i);
}

TEST(WorkerPoolTest, ThreadsRunAtTheGivenNicenessAndTheCallersAreUntouched) {
  const int caller = getpriority(PRIO_PROCESS, static_cast<id_t>(gettid()));
  std::mutex mutex;
  std::vector<int> seen;
  {
    WorkerPool pool(2, 10);
    for (int i = 0; i < 8; ++i) {
      pool.Post([&] {
        const int nice = getpriority(PRIO_PROCESS, static_cast<id_t>(gettid()));
        std::lock_guard lock(mutex);
        seen.push_back(nice);
      });
    }
  }
  ASSERT_EQ(seen.size(), 8u);
  // Nice values add up to at most 19, so a caller already at 10 or more sees 19.
  for (const int nice : seen) EXPECT_EQ(nice, std::min(19, caller + 10));
  EXPECT_EQ(getpriority(PRIO_PROCESS, static_cast<id_t>(gettid())), caller);
}

}  // namespace
}  // namespace orbit::server
