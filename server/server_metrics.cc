#include "server/server_metrics.h"

#include <string>

#include "api/engine_names.h"
#include "server/model_catalogue.h"
#include "server/session_registry.h"
#include "server/worker_pool.h"

namespace orbit::server {
namespace {

// A descriptor frame costs tens of microseconds, an image frame milliseconds to a few hundred
// (decoding up to --max-image-pixels); a scrape interval holds hundreds of thousands of frames.
const std::vector<double> kFrameBounds = {1e-5, 2.5e-5, 5e-5,  1e-4, 2.5e-4, 5e-4, 1e-3, 2.5e-3,
                                          5e-3, 0.01,   0.025, 0.05, 0.1,    0.25, 0.5,  1};
// An enrollment describes up to hundreds of images and syncs the store: milliseconds to seconds.
const std::vector<double> kEnrollmentBounds = {0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1,
                                               0.25,  0.5,    1,     2.5,  5,     10,   30};
// One SQLite transaction with synchronous=FULL: an fsync or two, a fraction of a millisecond on
// an SSD, tens of milliseconds on a disk or a busy store.
const std::vector<double> kStoreWriteBounds = {1e-4,  2.5e-4, 5e-4, 0.001, 0.0025, 0.005, 0.01,
                                               0.025, 0.05,   0.1,  0.25,  0.5,    1,     5};

}  // namespace

ServerMetrics::ServerMetrics()
    : frames_family_(registry_.AddCounter(
          "orbit_frames_processed_total",
          "Frames the engines processed (Session streams and Recognize calls), by engine.",
          {"engine"})),
      frame_seconds_family_(registry_.AddHistogram(
          "orbit_frame_processing_seconds",
          "Server time per processed frame, from reading it to its update being ready (waiting "
          "for a worker, decoding, CEDD, the engine update: the update's processing_time_us), by "
          "how the frame was sent (cedd or image).",
          {"input"}, kFrameBounds)),
      open_sessions_family_(registry_.AddGauge("orbit_open_sessions", "Session streams open now.")),
      refusals_family_(registry_.AddCounter(
          "orbit_refusals_total",
          "Calls and streams the server ended with an error, by status code and the rule that "
          "refused them (docs/service.md lists the reasons).",
          {"code", "reason"})),
      enrollments_family_(registry_.AddCounter(
          "orbit_enrollments_total",
          "Enroll calls, by outcome: stored, refused, failed (store or server), cancelled (the "
          "client's stream broke).",
          {"outcome"})),
      enrollment_seconds_family_(registry_.AddHistogram(
          "orbit_enrollment_seconds",
          "Server time from the end of an Enroll stream to its answer (describing uploaded "
          "images, the durable store write, indexing), of enrollments stored.",
          {}, kEnrollmentBounds)),
      index_objects_family_(
          registry_.AddGauge("orbit_index_objects", "Objects in the index sessions rank.")),
      index_views_family_(
          registry_.AddGauge("orbit_index_views", "Views of every object in the index.")),
      store_write_seconds_family_(registry_.AddHistogram(
          "orbit_store_write_seconds",
          "Duration of each committed write to the model store (one transaction, synced to "
          "disk), by operation: enroll, add_views, delete.",
          {"operation"}, kStoreWriteBounds)),
      queue_depth_family_(registry_.AddGauge(
          "orbit_worker_queue_depth",
          "Tasks waiting for a worker thread, by pool: workers (descriptor frames, short calls; "
          "--workers) and bulk_workers (image frames, enrollments; --bulk-workers).",
          {"pool"})) {
  for (const std::string& name : SessionEngineNames()) {
    frames_[ParseSessionEngine(name)] = &frames_family_.WithLabels({name});
  }
  frame_seconds_[static_cast<int>(FrameInput::kCedd)] = &frame_seconds_family_.WithLabels({"cedd"});
  frame_seconds_[static_cast<int>(FrameInput::kImage)] =
      &frame_seconds_family_.WithLabels({"image"});
  for (const auto& [code, reason] : kRefusalKinds) {
    refusals_[code][static_cast<int>(reason)] =
        &refusals_family_.WithLabels({StatusCodeName(code), RefusalReasonName(reason)});
  }
  enrollments_[static_cast<int>(EnrollmentOutcome::kStored)] =
      &enrollments_family_.WithLabels({"stored"});
  enrollments_[static_cast<int>(EnrollmentOutcome::kRefused)] =
      &enrollments_family_.WithLabels({"refused"});
  enrollments_[static_cast<int>(EnrollmentOutcome::kFailed)] =
      &enrollments_family_.WithLabels({"failed"});
  enrollments_[static_cast<int>(EnrollmentOutcome::kCancelled)] =
      &enrollments_family_.WithLabels({"cancelled"});
  enrollment_seconds_ = &enrollment_seconds_family_.WithLabels({});
  store_writes_.enroll = &store_write_seconds_family_.WithLabels({"enroll"});
  store_writes_.add_views = &store_write_seconds_family_.WithLabels({"add_views"});
  store_writes_.remove = &store_write_seconds_family_.WithLabels({"delete"});
}

FrameMetrics ServerMetrics::ForEngine(v1::Engine engine) {
  FrameMetrics metrics;
  const bool known = engine >= 0 && engine < v1::Engine_ARRAYSIZE && frames_[engine] != nullptr;
  metrics.frames_ = known ? frames_[engine] : &frames_family_.WithLabels({"unknown"});
  metrics.seconds_ = frame_seconds_;
  return metrics;
}

grpc::Status ServerMetrics::Refuse(grpc::Status status, RefusalReason reason) {
  if (!status.ok()) CountRefusal(status.error_code(), reason);
  return status;
}

void ServerMetrics::CountRefusal(grpc::StatusCode code, RefusalReason reason) {
  const int c = static_cast<int>(code), r = static_cast<int>(reason);
  Counter* counter = c > 0 && c < kStatusCodes ? refusals_[c][r] : nullptr;
  if (counter == nullptr) {  // a pair outside kRefusalKinds: found (or created) under a lock
    counter = &refusals_family_.WithLabels({StatusCodeName(code), RefusalReasonName(reason)});
  }
  counter->Increment();
}

void ServerMetrics::CountEnrollment(EnrollmentOutcome outcome) {
  enrollments_[static_cast<int>(outcome)]->Increment();
}

void ServerMetrics::WatchSessions(const SessionRegistry& sessions) {
  open_sessions_family_.Add({}, [&sessions] { return static_cast<double>(sessions.size()); });
}

void ServerMetrics::WatchIndex(const ModelCatalogue& catalogue) {
  index_objects_family_.Add(
      {}, [&catalogue] { return static_cast<double>(catalogue.Snapshot()->object_count()); });
  index_views_family_.Add(
      {}, [&catalogue] { return static_cast<double>(catalogue.Snapshot()->view_count()); });
}

void ServerMetrics::WatchWorkers(const WorkerPool& workers, const WorkerPool& bulk_workers) {
  queue_depth_family_.Add({"workers"},
                          [&workers] { return static_cast<double>(workers.queued()); });
  queue_depth_family_.Add({"bulk_workers"},
                          [&bulk_workers] { return static_cast<double>(bulk_workers.queued()); });
}

}  // namespace orbit::server
