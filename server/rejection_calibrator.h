// RejectionCalibrator: the server's calibration of the calibrated accept / unknown rule
// (core/decision/rejection_calibration.h), kept in step with the model set without making sessions
// wait for it.
//
// Computed once for the index the server starts with (before it serves), then again in the
// background once a session shows it a snapshot that differs enough from the one it was
// computed from (RecalibrationDue): an enrollment or deletion, from any source. Sessions keep
// the previous calibration until the new one is ready (what it costs: rejection-calibration in
// docs/results/recognition.md, "Cost"; docs/service.md). A session waits only for the
// very first calibration, when the server started with fewer than two objects. A burst of
// changes costs one recalibration per change it cannot coalesce, on one thread that runs on the
// core's idle time (SCHED_IDLE, thread_priority.h) once there is a calibration, so it never
// takes the core from a session; the first calibration, which sessions wait for, is made at
// their priority (docs/design.md#recalibration);
// it still streams the whole model set through the caches, which slows the sessions' frames
// while it runs (docs/results/load.md, "At 1000 objects with the product default, again"),
// hence the wait for a change worth it.
//
// Thread-safe.
#pragma once

#include <sys/types.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <thread>

#include "core/base/mutex.h"
#include "core/decision/rejection_calibration.h"
#include "core/index/view_index.h"

namespace orbit::server {

// One object more or less barely moves a threshold set by the whole model set (the null draws
// about 2 views per object at 1000 objects): a recalibration is due once the model set has
// changed by at least 1% of the objects it was calibrated on (at least 1 change: every change
// up to 100 objects), or a change has waited kMaxRecalibrationDelaySeconds, or there is no
// calibration yet. `changes` counts publications since the calibrated snapshot (snapshot
// serials), so it may overcount, never undercount.
inline constexpr double kRecalibrationShare = 0.01;
inline constexpr int kMaxRecalibrationDelaySeconds = 300;
bool RecalibrationDue(std::uint64_t changes, int calibrated_objects, double waited_seconds,
                      bool calibrated);

class RejectionCalibrator {
 public:
  // Calibrates `initial` before returning, on every CPU the process may use (whatever
  // `options.threads` says), and starts the background thread, whose recalibrations use
  // `options` as given, at idle priority once a calibration exists.
  explicit RejectionCalibrator(std::shared_ptr<const ViewIndexSnapshot> initial,
                               CalibrationOptions options = {});
  // Stops the background thread (a recalibration under way is finished first).
  ~RejectionCalibrator();

  RejectionCalibrator(const RejectionCalibrator&) = delete;
  RejectionCalibrator& operator=(const RejectionCalibrator&) = delete;

  // The latest calibration. When `current` is newer than what it was computed from, asks for a
  // recalibration of `current` in the background, and waits for it only when there is no
  // calibration yet (the server started with fewer than two objects) and `current` can have one.
  std::shared_ptr<const RejectionCalibration> For(
      const std::shared_ptr<const ViewIndexSnapshot>& current) ABSL_LOCKS_EXCLUDED(mutex_);

  // Waits until the calibration in use was computed from `snapshot` or a later one (tests).
  // Tests only. The first form waits as long as it takes (a change that is not due yet waits up
  // to kMaxRecalibrationDelaySeconds); the second at most `timeout`, and says whether it got there.
  void TEST_WaitFor(const ViewIndexSnapshot& snapshot) ABSL_LOCKS_EXCLUDED(mutex_);
  bool TEST_WaitFor(const ViewIndexSnapshot& snapshot, std::chrono::milliseconds timeout)
      ABSL_LOCKS_EXCLUDED(mutex_);
  // The background thread's scheduling policy as Linux holds it (SCHED_IDLE, SCHED_OTHER), or -1
  // when it cannot be read. Tests only.
  int TEST_SchedulingPolicy();

 private:
  void Run() ABSL_LOCKS_EXCLUDED(mutex_);
  // Waits until a recalibration is due and takes its snapshot off requested_; null once stopped.
  std::shared_ptr<const ViewIndexSnapshot> NextDue() ABSL_LOCKS_EXCLUDED(mutex_);
  // RecalibrationDue for requested_, now. REQUIRES: requested_ is not null.
  bool RequestDue() const ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_);
  // Whether the calibration in use was computed from `snapshot` or a later one, or stop_.
  bool CalibratedFor(const ViewIndexSnapshot& snapshot) const ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_);

  const CalibrationOptions options_;
  Mutex mutex_;
  CondVar wake_;  // a request or stop
  CondVar done_;  // a recalibration finished
  std::shared_ptr<const RejectionCalibration> calibration_ ABSL_GUARDED_BY(mutex_);
  std::uint64_t calibrated_serial_ ABSL_GUARDED_BY(mutex_) = 0;
  int calibrated_objects_ ABSL_GUARDED_BY(mutex_) = 0;
  std::shared_ptr<const ViewIndexSnapshot> requested_ ABSL_GUARDED_BY(mutex_);     // null: none
  std::chrono::steady_clock::time_point first_requested_ ABSL_GUARDED_BY(mutex_);  // pending since
  bool stop_ ABSL_GUARDED_BY(mutex_) = false;
  std::atomic<pid_t> thread_id_ = 0;  // the background thread's Linux id, once it runs (tests)
  std::thread thread_;
};

}  // namespace orbit::server
