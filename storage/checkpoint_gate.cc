#include "storage/checkpoint_gate.h"

namespace orbit {

void CheckpointGate::EnterRead() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return !exclusive_; });
  ++reads_in_flight_;
}

void CheckpointGate::LeaveRead() {
  std::lock_guard lock(mutex_);
  if (--reads_in_flight_ == 0) changed_.notify_all();
}

void CheckpointGate::RunExclusive(const std::function<void()>& section) {
  {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [this] { return !exclusive_; });
    exclusive_ = true;
    changed_.wait(lock, [this] { return reads_in_flight_ == 0; });
  }
  struct Reopen {  // lets reads in again however `section` ends
    CheckpointGate& gate;
    ~Reopen() {
      std::lock_guard lock(gate.mutex_);
      gate.exclusive_ = false;
      gate.changed_.notify_all();
    }
  } reopen{*this};
  section();
}

}  // namespace orbit
