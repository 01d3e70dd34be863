// WorkerPool: a fixed set of threads running queued tasks in arrival order. The server runs
// engine work, image decoding and store writes here, so gRPC's reactor threads never block.
//
// Thread-safe: Post() may be called from any thread, including from a task.
#pragma once

#include <deque>
#include <functional>
#include <thread>
#include <vector>

#include "core/base/mutex.h"

namespace orbit::server {

class WorkerPool {
 public:
  // REQUIRES: threads >= 1. The threads run `nice` steps nicer than the thread that creates
  // the pool (Linux's per-thread priority, capped at 19): the bulk pool's image decoding and
  // enrollments yield a busy core to the sessions' descriptor frames, and still get the time the
  // frames leave.
  explicit WorkerPool(int threads, int nice = 0);
  // Runs every task already posted, then joins the threads.
  ~WorkerPool();

  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  // Queues `task`. A task must not throw (the pool terminates the process if one does).
  void Post(std::function<void()> task) ABSL_LOCKS_EXCLUDED(mutex_);

  int size() const { return static_cast<int>(threads_.size()); }

  // The tasks posted but not yet started (the pool's queue depth). Takes the pool's lock.
  int queued() const ABSL_LOCKS_EXCLUDED(mutex_);

 private:
  void Run() ABSL_LOCKS_EXCLUDED(mutex_);

  mutable Mutex mutex_;
  CondVar wake_;
  std::deque<std::function<void()>> tasks_ ABSL_GUARDED_BY(mutex_);
  bool stopping_ ABSL_GUARDED_BY(mutex_) = false;
  std::vector<std::thread> threads_;  // set by the constructor
};

}  // namespace orbit::server
