// CheckpointGate: lets the store's writer briefly stop the store's own readers so that a
// checkpoint can reset the write-ahead log.
//
// Why: SQLite can only restart the log from its beginning once no reader uses it. Readers that
// overlap without pause (a busy server loading snapshots, listing, backing up) keep some part of
// the log in use forever, so passive checkpoints never let it restart and it grows without bound;
// a RESTART checkpoint waiting on them through the busy handler waits its full timeout. The gate
// drains this process's readers instead: new reads wait, reads in flight finish, the checkpoint
// runs (milliseconds), reads resume. Writer-preferring, so a stream of readers cannot starve it.
//
// Thread-safe.
#pragma once

#include <functional>

#include "core/base/mutex.h"

namespace orbit {

class CheckpointGate {
 public:
  // Brackets one read. EnterRead waits while an exclusive section is pending or running.
  void EnterRead() ABSL_LOCKS_EXCLUDED(mutex_);
  void LeaveRead() ABSL_LOCKS_EXCLUDED(mutex_);

  // Runs `section` once no read is in flight, holding new reads back until it returns.
  // REQUIRES: the calling thread is not inside a read.
  void RunExclusive(const std::function<void()>& section) ABSL_LOCKS_EXCLUDED(mutex_);

 private:
  // Lets reads in again and wakes the waiters.
  void EndExclusive() ABSL_LOCKS_EXCLUDED(mutex_);

  Mutex mutex_;  // never held while `section` runs
  CondVar changed_;
  int reads_in_flight_ ABSL_GUARDED_BY(mutex_) = 0;
  bool exclusive_ ABSL_GUARDED_BY(mutex_) = false;  // pending or running
};

}  // namespace orbit
