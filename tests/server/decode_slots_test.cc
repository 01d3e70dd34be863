// The decode slots (server/decode_slots.h): at most their capacity held at once, one per core
// for the process.
#include "server/decode_slots.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <optional>
#include <thread>

#include <gtest/gtest.h>

namespace orbit::server {
namespace {

TEST(DecodeSlotsTest, AdmitAtMostTheirCapacityAndWakeAWaiter) {
  DecodeSlots slots(2);
  EXPECT_EQ(slots.capacity(), 2);
  DecodeSlots::Slot first = slots.Acquire();
  std::optional<DecodeSlots::Slot> second = slots.Acquire();
  std::atomic<bool> third_held = false;
  std::thread waiter([&] {
    DecodeSlots::Slot third = slots.Acquire();
    third_held = true;
  });
  // Both slots are held: the waiter cannot get one, however long it is given.
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_FALSE(third_held);
  second.reset();  // frees one
  waiter.join();
  EXPECT_TRUE(third_held);
  // The waiter's slot went back when it ended, and a slot moved from is held once: with `first`
  // held, exactly one more can be taken (a second Acquire here would wait for ever).
  DecodeSlots::Slot again = slots.Acquire();
  DecodeSlots::Slot moved = std::move(again);
  moved = DecodeSlots::Slot();  // gives it back
  DecodeSlots::Slot last = slots.Acquire();
}

TEST(DecodeSlotsTest, TheProcessDecodesAtMostOneImagePerCore) {
  EXPECT_EQ(ProcessDecodeSlots().capacity(),
            static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
  EXPECT_EQ(&ProcessDecodeSlots(), &ProcessDecodeSlots());
}

}  // namespace
}  // namespace orbit::server
