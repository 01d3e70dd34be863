// WorkerPool (server/worker_pool.h): stream work before calls, calls bounded, everything not
// started abandoned (not run) when the pool stops, and the bulk pool's threads at the niceness
// they were given.
#include "server/worker_pool.h"

#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <future>
#include <mutex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace orbit::server {
namespace {

// A pool whose one thread is held by a task until Release(), so that what is posted meanwhile
// queues.
class HeldPool {
 public:
  explicit HeldPool(int max_queued_calls) : pool(1, 0, max_queued_calls) {
    pool.Post({.run = [this] { release_.get_future().wait(); }, .abandon = [] {}});
    while (pool.queued() > 0) std::this_thread::yield();  // the holding task has started
  }
  void Release() { release_.set_value(); }
  WorkerPool pool;

 private:
  std::promise<void> release_;
};

TEST(WorkerPoolTest, StreamWorkRunsBeforeQueuedCallsAndEachQueueInArrivalOrder) {
  std::vector<std::string> order;  // written by the pool's one thread, read after the join
  std::atomic<int> ran{0};
  {
    HeldPool held(10);
    const auto task = [&](std::string name) {
      return WorkerPool::Task{.run =
                                  [&order, &ran, name] {
                                    order.push_back(name);
                                    ++ran;
                                  },
                              .abandon = [] {}};
    };
    EXPECT_TRUE(held.pool.TryPost(task("call 1")));
    held.pool.Post(task("frame 1"));
    EXPECT_TRUE(held.pool.TryPost(task("call 2")));
    held.pool.Post(task("frame 2"));
    EXPECT_EQ(held.pool.queued(), 4);
    held.Release();
    while (ran < 4) std::this_thread::yield();
  }
  EXPECT_EQ(order, (std::vector<std::string>{"frame 1", "frame 2", "call 1", "call 2"}));
}

TEST(WorkerPoolTest, RefusesACallBeyondItsQueueAndStillTakesStreamWork) {
  HeldPool held(2);
  std::atomic<int> ran{0};
  const WorkerPool::Task count{.run = [&ran] { ++ran; }, .abandon = [] {}};
  EXPECT_TRUE(held.pool.TryPost(count));
  EXPECT_TRUE(held.pool.TryPost(count));
  EXPECT_FALSE(held.pool.TryPost(count)) << "a third call waits beyond max_queued_calls 2";
  held.pool.Post(count);  // a session's frame is never refused for the calls' queue
  EXPECT_EQ(held.pool.queued(), 3);
  held.Release();
  while (ran < 3) std::this_thread::yield();
  EXPECT_TRUE(held.pool.TryPost(count)) << "room again once the queue drained";
}

TEST(WorkerPoolTest, StopAbandonsWhatHasNotStartedAndEverythingPostedLater) {
  std::vector<std::string> abandoned;
  std::atomic<int> ran{0};
  HeldPool held(10);
  const auto task = [&](std::string name) {
    return WorkerPool::Task{.run = [&ran] { ++ran; },
                            .abandon = [&abandoned, name] { abandoned.push_back(name); }};
  };
  EXPECT_TRUE(held.pool.TryPost(task("call")));
  held.pool.Post(task("frame"));
  held.pool.Stop();
  EXPECT_EQ(abandoned, (std::vector<std::string>{"frame", "call"}));
  EXPECT_TRUE(held.pool.TryPost(task("late call")));
  held.pool.Post(task("late frame"));
  EXPECT_EQ(abandoned, (std::vector<std::string>{"frame", "call", "late call", "late frame"}));
  EXPECT_EQ(held.pool.queued(), 0);
  held.Release();  // the running task ends; the destructor joins
  EXPECT_EQ(ran, 0);
}

TEST(WorkerPoolTest, ThreadsRunAtTheGivenNicenessAndTheCallersAreUntouched) {
  const int caller = getpriority(PRIO_PROCESS, static_cast<id_t>(gettid()));
  std::mutex mutex;
  std::vector<int> seen;
  {
    WorkerPool pool(2, 10, 8);
    for (int i = 0; i < 8; ++i) {
      pool.Post({.run =
                     [&] {
                       const int nice = getpriority(PRIO_PROCESS, static_cast<id_t>(gettid()));
                       std::lock_guard lock(mutex);
                       seen.push_back(nice);
                     },
                 .abandon = [] {}});
    }
    while (true) {
      std::lock_guard lock(mutex);
      if (seen.size() == 8u) break;
    }
  }
  ASSERT_EQ(seen.size(), 8u);
  // Nice values add up to at most 19, so a caller already at 10 or more sees 19.
  for (const int nice : seen) EXPECT_EQ(nice, std::min(19, caller + 10));
  EXPECT_EQ(getpriority(PRIO_PROCESS, static_cast<id_t>(gettid())), caller);
}

}  // namespace
}  // namespace orbit::server
