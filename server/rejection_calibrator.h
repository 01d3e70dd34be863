// RejectionCalibrator: the server's calibration of the calibrated accept / unknown rule
// (core/rejection_calibration.h), kept in step with the model set without making sessions wait
// for it.
//
// Computed once for the index the server starts with (before it serves), then again in the
// background whenever a session shows it a snapshot newer than the one it was computed from:
// an enrollment or deletion, from any source. Sessions keep the previous calibration until the
// new one is ready (137 ms at 100 objects, 1.73 s at 1000 on one core: rejection-calibration in
// docs/results/recognition.md); one object more or less barely moves a threshold set by the
// whole model set. A session waits only for the very first calibration, when the server started
// with fewer than two objects. A burst of changes costs one recalibration per change it cannot
// coalesce, on one thread, the least favoured by the scheduler (nice 19): it takes the core's idle
// time, so it never delays a session's frame, and finishes later when the core is busy.
//
// Thread-safe.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <thread>

#include "core/rejection_calibration.h"
#include "core/view_index.h"

namespace orbit::server {

class RejectionCalibrator {
 public:
  // Calibrates `initial` before returning and starts the background thread.
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
      const std::shared_ptr<const ViewIndexSnapshot>& current);

  // Waits until the calibration in use was computed from `snapshot` or a later one (tests).
  void TEST_WaitFor(const ViewIndexSnapshot& snapshot);

 private:
  void Run();

  const CalibrationOptions options_;
  std::mutex mutex_;
  std::condition_variable wake_;   // a request or stop
  std::condition_variable done_;   // a recalibration finished
  std::shared_ptr<const RejectionCalibration> calibration_;  // guarded by mutex_
  std::uint64_t calibrated_serial_ = 0;                       // guarded by mutex_
  std::shared_ptr<const ViewIndexSnapshot> requested_;        // guarded by mutex_; null: none
  bool stop_ = false;                                         // guarded by mutex_
  std::thread thread_;
};

}  // namespace orbit::server
