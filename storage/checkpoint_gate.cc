#include "storage/checkpoint_gate.h"

namespace orbit {

void CheckpointGate::EnterRead() {
  MutexLock lock(&mutex_);
  while (exclusive_) changed_.Wait(&mutex_);
  ++reads_in_flight_;
}

void CheckpointGate::LeaveRead() {
  MutexLock lock(&mutex_);
  if (--reads_in_flight_ == 0) changed_.SignalAll();
}

void CheckpointGate::RunExclusive(const std::function<void()>& section) {
  {
    MutexLock lock(&mutex_);
    while (exclusive_) changed_.Wait(&mutex_);
    exclusive_ = true;
    while (reads_in_flight_ != 0) changed_.Wait(&mutex_);
  }
  struct Reopen {  // lets reads in again however `section` ends
    CheckpointGate& gate;
    ~Reopen() { gate.EndExclusive(); }
  } reopen{*this};
  section();
}

void CheckpointGate::EndExclusive() {
  MutexLock lock(&mutex_);
  exclusive_ = false;
  changed_.SignalAll();
}

}  // namespace orbit
