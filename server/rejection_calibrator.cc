#include "server/rejection_calibrator.h"

#include <utility>

#include "server/thread_priority.h"

namespace orbit::server {

RejectionCalibrator::RejectionCalibrator(std::shared_ptr<const ViewIndexSnapshot> initial,
                                         CalibrationOptions options)
    : options_(options),
      calibration_(std::make_shared<const RejectionCalibration>(
          RejectionCalibration::FromIndex(*initial, options))),
      calibrated_serial_(initial->serial()),
      thread_([this] { Run(); }) {}

RejectionCalibrator::~RejectionCalibrator() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

std::shared_ptr<const RejectionCalibration> RejectionCalibrator::For(
    const std::shared_ptr<const ViewIndexSnapshot>& current) {
  std::unique_lock lock(mutex_);
  // Snapshot serials grow with every publication, so a larger one is a newer model set.
  if (current->serial() > calibrated_serial_ &&
      (requested_ == nullptr || current->serial() > requested_->serial())) {
    requested_ = current;
    wake_.notify_one();
  }
  // With no calibration at all yet (the server started with fewer than two objects), the first
  // one is worth the wait: every decision would be UNDECIDED without it.
  if (!calibration_->calibrated() && current->object_count() >= 2) {
    done_.wait(lock, [&] { return calibrated_serial_ >= current->serial() || stop_; });
  }
  return calibration_;
}

void RejectionCalibrator::TEST_WaitFor(const ViewIndexSnapshot& snapshot) {
  std::unique_lock lock(mutex_);
  done_.wait(lock, [&] { return calibrated_serial_ >= snapshot.serial() || stop_; });
}

void RejectionCalibrator::Run() {
  // As nice as a thread gets: a recalibration is seconds of CPU at 1000 objects (1.8 s), and on
  // a busy core at the sessions' priority it would delay their frames by scheduler slices
  // (256 sessions x 10 frames/s with a 72-view enrollment every 5 s: p99 round trip 10-16 ms
  // instead of under 1). Sessions keep the previous calibration meanwhile.
  LowerThisThreadsPriority(19);
  std::unique_lock lock(mutex_);
  while (true) {
    wake_.wait(lock, [this] { return stop_ || requested_ != nullptr; });
    if (stop_) return;
    const std::shared_ptr<const ViewIndexSnapshot> snapshot = std::move(requested_);
    requested_ = nullptr;
    lock.unlock();
    auto calibration = std::make_shared<const RejectionCalibration>(
        RejectionCalibration::FromIndex(*snapshot, options_));
    lock.lock();
    calibration_ = std::move(calibration);
    calibrated_serial_ = snapshot->serial();
    done_.notify_all();
  }
}

}  // namespace orbit::server
