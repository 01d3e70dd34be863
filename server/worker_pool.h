// WorkerPool: a fixed set of threads running queued tasks. The server runs engine work, image
// decoding and store writes here, so gRPC's reactor threads never block.
//
// Two kinds of task, in two queues (docs/design.md#work-queues):
// - Stream work (Post): a session's image frame, an enrollment's commit. Each stream has at most
//   one task queued, and the streams are bounded by their own limits, so this queue is not capped.
//   It runs first: a device in a session, or an operator enrolling, waits behind no batch call.
// - Calls (TryPost): a unary call's whole work. At most `max_queued_calls` wait; beyond that
//   TryPost refuses, and the caller answers RESOURCE_EXHAUSTED at once instead of holding the
//   request's memory in an unbounded queue.
// Each task comes with what to do instead of running it (`abandon`): Stop() abandons everything
// not started, so that a shutdown answers queued work at once rather than running it.
//
// Thread-safe: Post() and TryPost() may be called from any thread, including from a task.
#pragma once

#include <deque>
#include <functional>
#include <thread>
#include <vector>

#include "core/base/mutex.h"

namespace orbit::server {

class WorkerPool {
 public:
  // What a task does, and what is done instead when the pool stops before it starts (it
  // must answer the call or the stream the task was for). Neither may throw (the pool terminates
  // the process if one does).
  struct Task {
    std::function<void()> run;
    std::function<void()> abandon;
  };

  // REQUIRES: threads >= 1, max_queued_calls >= 0. The threads run `nice` steps nicer than the
  // thread that creates the pool (Linux's per-thread priority, capped at 19): the bulk pool's
  // image decoding and enrollments yield a busy core to the sessions' descriptor frames, and still
  // get the time the frames leave.
  WorkerPool(int threads, int nice, int max_queued_calls);
  // Stop(), then joins the threads once the running tasks end.
  ~WorkerPool();

  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  // Queues stream work, ahead of every queued call. After Stop(), abandons it at once.
  void Post(Task task) ABSL_LOCKS_EXCLUDED(mutex_);
  // Queues a call's work; false (nothing queued, nothing called) when max_queued_calls calls
  // already wait. After Stop(), abandons it at once and returns true.
  bool TryPost(Task task) ABSL_LOCKS_EXCLUDED(mutex_);

  // Abandons every task not started, in the order queued, and every task posted from now on;
  // tasks running go on. Called by the server's shutdown.
  void Stop() ABSL_LOCKS_EXCLUDED(mutex_);

  int size() const { return static_cast<int>(threads_.size()); }
  int max_queued_calls() const { return max_queued_calls_; }

  // The tasks posted but not yet started, both queues (the pool's queue depth). Takes the lock.
  int queued() const ABSL_LOCKS_EXCLUDED(mutex_);

 private:
  void Run() ABSL_LOCKS_EXCLUDED(mutex_);

  const int max_queued_calls_;
  mutable Mutex mutex_;
  CondVar wake_;
  std::deque<Task> stream_work_ ABSL_GUARDED_BY(mutex_);
  std::deque<Task> calls_ ABSL_GUARDED_BY(mutex_);
  bool stopping_ ABSL_GUARDED_BY(mutex_) = false;
  std::vector<std::thread> threads_;  // set by the constructor
};

}  // namespace orbit::server
