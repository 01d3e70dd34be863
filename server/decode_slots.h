// DecodeSlots: how many images the process decodes at once.
#pragma once

#include "core/base/mutex.h"

namespace orbit::server {

// A counting semaphore over decodes: at most `slots` holders at once; Acquire() blocks (on a
// condition variable: it sleeps, it never spins) until one is free. A slot is held for the whole
// life of a decoded image (decode, then description), so `slots` x ServerLimits::max_image_pixels
// x 8 bytes (4 channels of 16 bits, the most OpenCV decodes a PNG or JPEG to) bounds the
// memory decoded images hold at once. Holders must not wait for anything else while holding a
// slot (no deadlock is possible then). Thread-safe.
class DecodeSlots {
 public:
  // A held slot, released when destroyed. Movable; an empty (default or moved-from) Slot holds
  // nothing.
  class [[nodiscard]] Slot {
   public:
    Slot() = default;
    Slot(Slot&& other) noexcept : owner_(other.owner_) { other.owner_ = nullptr; }
    Slot& operator=(Slot&& other) noexcept;
    Slot(const Slot&) = delete;
    Slot& operator=(const Slot&) = delete;
    ~Slot();

   private:
    friend class DecodeSlots;
    explicit Slot(DecodeSlots* owner) : owner_(owner) {}
    DecodeSlots* owner_ = nullptr;
  };

  // REQUIRES: slots >= 1.
  explicit DecodeSlots(int slots);
  // REQUIRES: no Slot of this object is held.
  ~DecodeSlots() = default;

  DecodeSlots(const DecodeSlots&) = delete;
  DecodeSlots& operator=(const DecodeSlots&) = delete;

  // Waits until a slot is free, then holds it.
  Slot Acquire() ABSL_LOCKS_EXCLUDED(mutex_);

  // The number of slots, held or free.
  int capacity() const { return capacity_; }

 private:
  void Release() ABSL_LOCKS_EXCLUDED(mutex_);

  const int capacity_;
  Mutex mutex_;
  CondVar freed_;
  int free_ ABSL_GUARDED_BY(mutex_);
};

// The decode slots every image decoded by this process goes through: one per core
// (AvailableCpus, core/base/parallel_for.h: the CPUs this process may run on). Decoding is
// CPU-bound, so more decodes at once than cores would not finish sooner; they would only hold more
// memory. The worker pool already bounds decodes by its size; these slots keep the bound when
// --workers is above the core count.
DecodeSlots& ProcessDecodeSlots();

}  // namespace orbit::server
