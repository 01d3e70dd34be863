#include "server/rejection_calibrator.h"

#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <utility>

#include "core/base/parallel_for.h"
#include "server/thread_priority.h"

namespace orbit::server {
namespace {

// The first calibration runs before the server serves, when nothing else needs the CPUs.
CalibrationOptions OnEveryCpu(CalibrationOptions options) {
  options.threads = AvailableCpus();
  return options;
}

}  // namespace

RejectionCalibrator::RejectionCalibrator(std::shared_ptr<const ViewIndexSnapshot> initial,
                                         CalibrationOptions options)
    : options_(options),
      calibration_(std::make_shared<const RejectionCalibration>(
          RejectionCalibration::FromIndex(*initial, OnEveryCpu(options)))),
      calibrated_serial_(initial->serial()),
      calibrated_objects_(static_cast<int>(initial->object_count())),
      thread_([this] { Run(); }) {}

bool RecalibrationDue(std::uint64_t changes, int calibrated_objects, double waited_seconds,
                      bool calibrated) {
  if (changes == 0) return false;
  if (!calibrated) return true;
  const double needed = std::max(1.0, kRecalibrationShare * calibrated_objects);
  return static_cast<double>(changes) >= needed || waited_seconds >= kMaxRecalibrationDelaySeconds;
}

RejectionCalibrator::~RejectionCalibrator() {
  {
    MutexLock lock(&mutex_);
    stop_ = true;
  }
  wake_.SignalAll();
  done_.SignalAll();
  thread_.join();
}

std::shared_ptr<const RejectionCalibration> RejectionCalibrator::For(
    const std::shared_ptr<const ViewIndexSnapshot>& current) {
  MutexLock lock(&mutex_);
  // Snapshot serials grow with every publication, so a larger one is a newer model set.
  if (current->serial() > calibrated_serial_ &&
      (requested_ == nullptr || current->serial() > requested_->serial())) {
    if (requested_ == nullptr) first_requested_ = std::chrono::steady_clock::now();
    requested_ = current;
    wake_.Signal();
  }
  // With no calibration at all yet (the server started with fewer than two objects), the first
  // one is worth the wait: every decision would be UNDECIDED without it.
  if (!calibration_->calibrated() && current->object_count() >= 2) {
    while (!CalibratedFor(*current)) done_.Wait(&mutex_);
  }
  return calibration_;
}

bool RejectionCalibrator::CalibratedFor(const ViewIndexSnapshot& snapshot) const {
  return calibrated_serial_ >= snapshot.serial() || stop_;
}

void RejectionCalibrator::TEST_WaitFor(const ViewIndexSnapshot& snapshot) {
  MutexLock lock(&mutex_);
  while (!CalibratedFor(snapshot)) done_.Wait(&mutex_);
}

bool RejectionCalibrator::TEST_WaitFor(const ViewIndexSnapshot& snapshot,
                                       std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  MutexLock lock(&mutex_);
  while (!CalibratedFor(snapshot) && done_.WaitUntil(&mutex_, deadline)) {
  }
  return CalibratedFor(snapshot);
}

bool RejectionCalibrator::RequestDue() const {
  const std::chrono::duration<double> waited = std::chrono::steady_clock::now() - first_requested_;
  return RecalibrationDue(requested_->serial() - calibrated_serial_, calibrated_objects_,
                          waited.count(), calibration_->calibrated());
}

std::shared_ptr<const ViewIndexSnapshot> RejectionCalibrator::NextDue() {
  MutexLock lock(&mutex_);
  while (!stop_ && requested_ == nullptr) wake_.Wait(&mutex_);
  if (stop_) return nullptr;
  // A change too small to matter waits for more, or for its time.
  const auto deadline = first_requested_ + std::chrono::seconds(kMaxRecalibrationDelaySeconds);
  while (!stop_ && !RequestDue() && wake_.WaitUntil(&mutex_, deadline)) {
  }
  if (stop_) return nullptr;
  std::shared_ptr<const ViewIndexSnapshot> snapshot = std::move(requested_);
  requested_ = nullptr;
  return snapshot;
}

void RejectionCalibrator::Run() {
  // On the core's idle time once there is a calibration: a recalibration is seconds of CPU at
  // 1000 objects, and on a busy core at the sessions' priority, or even at nice 19, it delayed
  // their frames by scheduler slices (docs/results/load.md, "At 1000 objects with the product
  // default, again"). Sessions keep the previous calibration meanwhile. The first calibration is
  // different: sessions wait for it (For), and on a saturated machine idle time may never come,
  // so it is made at the sessions' priority (docs/design.md#recalibration).
  bool on_idle_time = false;
  auto move_to_idle_time = [&on_idle_time] {
    RunThisThreadOnIdleTime();
    on_idle_time = true;
  };
  {
    MutexLock lock(&mutex_);
    if (calibration_->calibrated()) move_to_idle_time();
  }
  thread_id_.store(gettid());  // after the first choice of priority, which tests read
  for (;;) {
    const std::shared_ptr<const ViewIndexSnapshot> snapshot = NextDue();
    if (snapshot == nullptr) return;
    auto calibration = std::make_shared<const RejectionCalibration>(
        RejectionCalibration::FromIndex(*snapshot, options_));
    // Before publishing, so that whoever waited for the first calibration finds the thread
    // already on idle time.
    if (!on_idle_time && calibration->calibrated()) move_to_idle_time();
    {
      MutexLock lock(&mutex_);
      calibration_ = std::move(calibration);
      calibrated_serial_ = snapshot->serial();
      calibrated_objects_ = static_cast<int>(snapshot->object_count());
    }
    done_.SignalAll();
  }
}

int RejectionCalibrator::TEST_SchedulingPolicy() {
  // By the thread's id, as Linux holds it: pthread_getschedparam answers from what glibc cached,
  // which sched_setscheduler does not update.
  while (thread_id_.load() == 0) std::this_thread::yield();
  return sched_getscheduler(thread_id_.load());
}

}  // namespace orbit::server
