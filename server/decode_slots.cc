#include "server/decode_slots.h"

#include "core/base/parallel_for.h"

namespace orbit::server {

DecodeSlots::DecodeSlots(int slots) : capacity_(slots), free_(slots) {}

DecodeSlots::Slot DecodeSlots::Acquire() {
  MutexLock lock(&mutex_);
  while (free_ <= 0) freed_.Wait(&mutex_);
  --free_;
  return Slot(this);
}

void DecodeSlots::Release() {
  {
    MutexLock lock(&mutex_);
    ++free_;
  }
  freed_.Signal();
}

DecodeSlots::Slot& DecodeSlots::Slot::operator=(Slot&& other) noexcept {
  if (this != &other) {
    if (owner_ != nullptr) owner_->Release();
    owner_ = other.owner_;
    other.owner_ = nullptr;
  }
  return *this;
}

DecodeSlots::Slot::~Slot() {
  if (owner_ != nullptr) owner_->Release();
}

DecodeSlots& ProcessDecodeSlots() {
  static DecodeSlots slots(AvailableCpus());
  return slots;
}

}  // namespace orbit::server
