// Mutex, MutexLock, CondVar (core/base/mutex.h): mutual exclusion, try-lock, waits that wake on
// a signal and return with the mutex held, timed waits that time out.
#include "core/base/mutex.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace orbit {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

// A counter whose increments are a read, a pause and a write: without exclusion, threads
// overwrite each other's increments.
class SlowCounter {
 public:
  void Increment() ABSL_LOCKS_EXCLUDED(mutex_) {
    MutexLock lock(&mutex_);
    const int value = value_;
    inside_.fetch_add(1);
    max_inside_ = std::max(max_inside_, inside_.load());
    std::this_thread::yield();
    inside_.fetch_sub(1);
    value_ = value + 1;
  }
  int value() ABSL_LOCKS_EXCLUDED(mutex_) {
    MutexLock lock(&mutex_);
    return value_;
  }
  int max_inside() ABSL_LOCKS_EXCLUDED(mutex_) {
    MutexLock lock(&mutex_);
    return max_inside_;
  }

 private:
  Mutex mutex_;
  std::atomic<int> inside_{0};
  int value_ ABSL_GUARDED_BY(mutex_) = 0;
  int max_inside_ ABSL_GUARDED_BY(mutex_) = 0;
};

TEST(MutexTest, MutexLockExcludesOtherThreads) {
  SlowCounter counter;
  constexpr int kThreads = 4;
  constexpr int kIncrements = 2000;
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&] {
      for (int i = 0; i < kIncrements; ++i) counter.Increment();
    });
  }
  for (std::thread& thread : threads) thread.join();
  EXPECT_EQ(counter.value(), kThreads * kIncrements);
  EXPECT_EQ(counter.max_inside(), 1);
}

TEST(MutexTest, MutexLockReleasesAtTheEndOfItsScope) {
  Mutex mutex;
  {
    MutexLock lock(&mutex);
    std::thread other([&] {
      const bool taken = mutex.TryLock();
      EXPECT_FALSE(taken);
      if (taken) mutex.Unlock();
    });
    other.join();
  }
  std::thread other([&] {
    const bool taken = mutex.TryLock();
    EXPECT_TRUE(taken);
    if (taken) mutex.Unlock();
  });
  other.join();
}

TEST(MutexTest, LockWaitsForTheHolder) {
  Mutex mutex;
  std::atomic<bool> released{false};
  std::atomic<bool> acquired_before_release{false};
  mutex.Lock();
  std::thread waiter([&] {
    MutexLock lock(&mutex);
    acquired_before_release = !released.load();
  });
  std::this_thread::sleep_for(50ms);
  released = true;
  mutex.Unlock();
  waiter.join();
  EXPECT_FALSE(acquired_before_release.load());
}

// One producer hands values to one consumer through a single slot: every value arrives once and
// in order only if each Wait wakes on the other side's signal and returns with the mutex held.
class Slot {
 public:
  void Put(int value) ABSL_LOCKS_EXCLUDED(mutex_) {
    MutexLock lock(&mutex_);
    while (full_) changed_.Wait(&mutex_);
    value_ = value;
    full_ = true;
    changed_.SignalAll();
  }
  int Take() ABSL_LOCKS_EXCLUDED(mutex_) {
    MutexLock lock(&mutex_);
    while (!full_) changed_.Wait(&mutex_);
    full_ = false;
    changed_.SignalAll();
    return value_;
  }

 private:
  Mutex mutex_;
  CondVar changed_;
  bool full_ ABSL_GUARDED_BY(mutex_) = false;
  int value_ ABSL_GUARDED_BY(mutex_) = 0;
};

TEST(CondVarTest, WaitWakesOnSignalWithTheMutexHeld) {
  Slot slot;
  constexpr int kValues = 5000;
  std::vector<int> taken;
  std::thread consumer([&] {
    for (int i = 0; i < kValues; ++i) taken.push_back(slot.Take());
  });
  for (int i = 0; i < kValues; ++i) slot.Put(i);
  consumer.join();
  ASSERT_EQ(taken.size(), static_cast<std::size_t>(kValues));
  for (int i = 0; i < kValues; ++i) ASSERT_EQ(taken[i], i);
}

// A gate every waiter passes once it opens.
class Gate {
 public:
  void Open() ABSL_LOCKS_EXCLUDED(mutex_) {
    {
      MutexLock lock(&mutex_);
      open_ = true;
    }
    opened_.SignalAll();  // the mutex need not be held
  }
  void Pass() ABSL_LOCKS_EXCLUDED(mutex_) {
    MutexLock lock(&mutex_);
    while (!open_) opened_.Wait(&mutex_);
  }
  // True when the gate opened before `deadline`.
  bool PassBy(Clock::time_point deadline) ABSL_LOCKS_EXCLUDED(mutex_) {
    MutexLock lock(&mutex_);
    while (!open_ && opened_.WaitUntil(&mutex_, deadline)) {
    }
    return open_;
  }

 private:
  Mutex mutex_;
  CondVar opened_;
  bool open_ ABSL_GUARDED_BY(mutex_) = false;
};

TEST(CondVarTest, SignalAllWakesEveryWaiter) {
  Gate gate;
  constexpr int kWaiters = 6;
  std::atomic<int> passed{0};
  std::vector<std::thread> waiters;
  for (int i = 0; i < kWaiters; ++i) {
    waiters.emplace_back([&] {
      gate.Pass();
      passed.fetch_add(1);
    });
  }
  std::this_thread::sleep_for(50ms);
  EXPECT_EQ(passed.load(), 0);
  gate.Open();
  for (std::thread& waiter : waiters) waiter.join();
  EXPECT_EQ(passed.load(), kWaiters);
}

TEST(CondVarTest, WaitUntilReturnsFalseAtItsDeadline) {
  Gate gate;
  const Clock::time_point start = Clock::now();
  EXPECT_FALSE(gate.PassBy(start + 100ms));
  EXPECT_GE(Clock::now() - start, 100ms);
}

TEST(CondVarTest, WaitUntilReturnsOnSignalBeforeItsDeadline) {
  Gate gate;
  std::thread opener([&] {
    std::this_thread::sleep_for(20ms);
    gate.Open();
  });
  const Clock::time_point start = Clock::now();
  EXPECT_TRUE(gate.PassBy(start + 30s));
  EXPECT_LT(Clock::now() - start, 10s);
  opener.join();
}

}  // namespace
}  // namespace orbit
