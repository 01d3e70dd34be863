// LowerThisThreadsPriority: the calling thread alone gets nicer, never past 19;
// RunThisThreadOnIdleTime: the calling thread alone moves to SCHED_IDLE.
#include "server/thread_priority.h"

#include <sched.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <thread>

#include <gtest/gtest.h>

namespace orbit::server {
namespace {

int ThisThreadsNice() { return getpriority(PRIO_PROCESS, static_cast<id_t>(gettid())); }

TEST(ThreadPriorityTest, OnlyTheCallingThreadGetsNicer) {
  const int caller = ThisThreadsNice();
  int after = 0;
  std::thread([&] {
    LowerThisThreadsPriority(5);
    after = ThisThreadsNice();
  }).join();
  EXPECT_EQ(after, std::min(19, caller + 5));
  EXPECT_EQ(ThisThreadsNice(), caller);
}

TEST(ThreadPriorityTest, StopsAtNineteenAndNeverRaises) {
  int capped = 0, unchanged = 0;
  std::thread([&] {
    LowerThisThreadsPriority(40);
    capped = ThisThreadsNice();
    LowerThisThreadsPriority(-10);  // not a way up
    unchanged = ThisThreadsNice();
  }).join();
  EXPECT_EQ(capped, 19);
  EXPECT_EQ(unchanged, 19);
}

TEST(ThreadPriorityTest, IdleTimeIsForTheCallingThreadOnly) {
  bool set = false;
  int policy = -1;
  std::thread([&] {
    set = RunThisThreadOnIdleTime();
    policy = sched_getscheduler(0);
  }).join();
  EXPECT_TRUE(set);  // Linux lets any thread lower itself to SCHED_IDLE
  EXPECT_EQ(policy, SCHED_IDLE);
  EXPECT_EQ(sched_getscheduler(0), SCHED_OTHER);
}

}  // namespace
}  // namespace orbit::server
