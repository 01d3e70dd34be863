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

#include <condition_variable>
#include <functional>
#include <mutex>

namespace orbit {

class CheckpointGate {
 public:
  // Brackets one read. EnterRead waits while an exclusive section is pending or running.
  void EnterRead();
  void LeaveRead();

  // Runs `section` once no read is in flight, holding new reads back until it returns.
  // REQUIRES: the calling thread is not inside a read.
  void RunExclusive(const std::function<void()>& section);

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  int reads_in_flight_ = 0;
  bool exclusive_ = false;  // pending or running
};

}  // namespace orbit
