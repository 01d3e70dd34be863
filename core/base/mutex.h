// Mutex, MutexLock, CondVar: a mutex the compiler knows as a lock, so that the rules of which lock
// guards what are annotations it checks rather than comments (docs/design.md#locking).
//
//   class Counter {
//    public:
//     void Add(int n) ABSL_LOCKS_EXCLUDED(mutex_) {
//       MutexLock lock(&mutex_);
//       total_ += n;
//       changed_.SignalAll();
//     }
//     void WaitFor(int n) ABSL_LOCKS_EXCLUDED(mutex_) {
//       MutexLock lock(&mutex_);
//       while (total_ < n) changed_.Wait(&mutex_);
//     }
//    private:
//     Mutex mutex_;
//     CondVar changed_;
//     int total_ ABSL_GUARDED_BY(mutex_) = 0;
//   };
//
// Clang's -Wthread-safety then rejects a read or write of total_ without mutex_ held, a call of
// a method marked ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_) without it, a call of one marked
// ABSL_LOCKS_EXCLUDED(mutex_) with it, and a lock taken twice or not released (the build-tsa step
// of scripts/test.sh). Other compilers ignore the annotations.
//
// A std::mutex and a std::condition_variable underneath: ThreadSanitizer, which intercepts the
// pthread calls they make, sees every lock and wait. Not recursive: locking a Mutex the thread
// already holds deadlocks.
//
// Waiting: CondVar::Wait takes the mutex (held by the caller) and returns with it held again,
// possibly without a signal, so a wait is a loop on its condition written in the caller, where
// the analysis checks the condition's reads:
//
//   while (!ready_) ready_changed_.Wait(&mutex_);
//   while (!ready_ && ready_changed_.WaitUntil(&mutex_, deadline)) {}  // false: deadline passed
#pragma once

#include <chrono>
#include <condition_variable>
#include <mutex>

#include <absl/base/thread_annotations.h>

namespace orbit {

class CondVar;

class ABSL_LOCKABLE Mutex {
 public:
  Mutex() = default;
  Mutex(const Mutex&) = delete;
  Mutex& operator=(const Mutex&) = delete;

  void Lock() ABSL_EXCLUSIVE_LOCK_FUNCTION() { mutex_.lock(); }
  void Unlock() ABSL_UNLOCK_FUNCTION() { mutex_.unlock(); }
  // Takes the lock when it is free; true when taken.
  bool TryLock() ABSL_EXCLUSIVE_TRYLOCK_FUNCTION(true) { return mutex_.try_lock(); }

  // Tells the analysis that the caller holds this mutex, where it cannot see it (a callback
  // that runs under the lock). Checks nothing at run time.
  void AssertHeld() const ABSL_ASSERT_EXCLUSIVE_LOCK() {}

 private:
  friend class CondVar;
  std::mutex mutex_;
};

// Holds `mutex` from its construction to the end of its scope.
class ABSL_SCOPED_LOCKABLE MutexLock {
 public:
  explicit MutexLock(Mutex* mutex) ABSL_EXCLUSIVE_LOCK_FUNCTION(mutex) : mutex_(mutex) {
    mutex_->Lock();
  }
  ~MutexLock() ABSL_UNLOCK_FUNCTION() { mutex_->Unlock(); }

  MutexLock(const MutexLock&) = delete;
  MutexLock& operator=(const MutexLock&) = delete;

 private:
  Mutex* const mutex_;
};

// A condition variable for a Mutex. Every wait on one CondVar must pass the same Mutex.
class CondVar {
 public:
  CondVar() = default;
  CondVar(const CondVar&) = delete;
  CondVar& operator=(const CondVar&) = delete;

  // Releases `mutex`, waits for a Signal or SignalAll (or a spurious wake-up), and takes
  // `mutex` again before returning.
  void Wait(Mutex* mutex) ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex) {
    std::unique_lock<std::mutex> lock(mutex->mutex_, std::adopt_lock);
    condition_.wait(lock);
    lock.release();  // still held: it is the caller's
  }

  // As Wait, but returns by `deadline` at the latest: false when it returned because the
  // deadline passed.
  template <class Clock, class Duration>
  bool WaitUntil(Mutex* mutex, const std::chrono::time_point<Clock, Duration>& deadline)
      ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex) {
    std::unique_lock<std::mutex> lock(mutex->mutex_, std::adopt_lock);
    const bool signalled = condition_.wait_until(lock, deadline) == std::cv_status::no_timeout;
    lock.release();
    return signalled;
  }

  // Wakes one waiting thread, if any. The caller may hold the mutex or not.
  void Signal() { condition_.notify_one(); }
  // Wakes every waiting thread.
  void SignalAll() { condition_.notify_all(); }

 private:
  std::condition_variable condition_;
};

}  // namespace orbit
