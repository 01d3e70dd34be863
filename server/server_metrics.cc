#include "server/server_metrics.h"

#include <prometheus/metric_family.h>
#include <prometheus/text_serializer.h>

#include <functional>
#include <sstream>
#include <string>
#include <utility>

#include "api/engines/engine_names.h"
#include "api/status_code_name.h"
#include "core/base/mutex.h"
#include "server/connection_admission.h"
#include "server/model_catalogue.h"
#include "server/session_registry.h"
#include "server/worker_pool.h"

namespace orbit::server {
namespace {

// A descriptor frame costs tens of microseconds, an image frame milliseconds to a few hundred
// (decoding up to --max-image-pixels); a scrape interval holds hundreds of thousands of frames.
const prometheus::Histogram::BucketBoundaries kFrameBounds = {
    1e-5, 2.5e-5, 5e-5,  1e-4, 2.5e-4, 5e-4, 1e-3, 2.5e-3,
    5e-3, 0.01,   0.025, 0.05, 0.1,    0.25, 0.5,  1};
// An enrollment describes up to hundreds of images and syncs the store: milliseconds to seconds.
const prometheus::Histogram::BucketBoundaries kEnrollmentBounds = {
    0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 0.5, 1, 2.5, 5, 10, 30};
// One SQLite transaction with synchronous=FULL: an fsync or two, a fraction of a millisecond on
// an SSD, tens of milliseconds on a disk or a busy store.
const prometheus::Histogram::BucketBoundaries kStoreWriteBounds = {
    1e-4, 2.5e-4, 5e-4, 0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 0.5, 1, 5};
// A change another replica committed reaches this one in milliseconds when it is woken by the
// notification, up to the poll interval (1 s) when it is not, and later while the store is away.
const prometheus::Histogram::BucketBoundaries kChangeLagBounds = {
    0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 0.5, 1, 2.5, 5, 10, 30};

prometheus::Family<prometheus::Counter>& AddCounter(prometheus::Registry& registry,
                                                    std::string name, std::string help) {
  return prometheus::BuildCounter().Name(std::move(name)).Help(std::move(help)).Register(registry);
}

prometheus::Family<prometheus::Histogram>& AddHistogram(prometheus::Registry& registry,
                                                        std::string name, std::string help) {
  return prometheus::BuildHistogram()
      .Name(std::move(name))
      .Help(std::move(help))
      .Register(registry);
}

}  // namespace

// Gauges whose values are read from the server's state when a scrape collects them, so that
// nothing on a hot path updates them. Families in the order of their first gauge.
class ServerMetrics::WatchedGauges final : public prometheus::Collectable {
 public:
  // A counter when `type` says so: a total the watched state keeps itself.
  void Add(const std::string& name, const std::string& help, prometheus::Labels labels,
           std::function<double()> read,
           prometheus::MetricType type = prometheus::MetricType::Gauge)
      ABSL_LOCKS_EXCLUDED(mutex_) {
    MutexLock lock(&mutex_);
    gauges_.push_back({name, help, std::move(labels), std::move(read), type});
  }

  std::vector<prometheus::MetricFamily> Collect() const ABSL_LOCKS_EXCLUDED(mutex_) override {
    MutexLock lock(&mutex_);
    std::vector<prometheus::MetricFamily> families;
    for (const Watched& gauge : gauges_) {
      if (families.empty() || families.back().name != gauge.name) {
        families.push_back({gauge.name, gauge.help, gauge.type, {}});
      }
      prometheus::ClientMetric metric;
      for (const auto& [name, value] : gauge.labels) metric.label.push_back({name, value});
      (gauge.type == prometheus::MetricType::Counter ? metric.counter.value : metric.gauge.value) =
          gauge.read();
      families.back().metric.push_back(std::move(metric));
    }
    return families;
  }

 private:
  struct Watched {
    std::string name, help;
    prometheus::Labels labels;
    std::function<double()> read;  // thread-safe and cheap: a scrape waits for it
    prometheus::MetricType type;
  };
  mutable Mutex mutex_;
  std::vector<Watched> gauges_ ABSL_GUARDED_BY(mutex_);  // a family's gauges are added together
};

ServerMetrics::ServerMetrics()
    : registry_(std::make_shared<prometheus::Registry>()),
      gauges_(std::make_shared<WatchedGauges>()),
      frames_family_(AddCounter(
          *registry_, "orbit_frames_processed_total",
          "Frames the engines processed (Session streams and Recognize calls), by engine.")),
      frame_seconds_family_(AddHistogram(
          *registry_, "orbit_frame_processing_seconds",
          "Server time per processed frame, from reading it to its update being ready (waiting "
          "for a worker, decoding, CEDD, the engine update: the update's processing_time_us), by "
          "how the frame was sent (cedd or image).")),
      refusals_family_(AddCounter(
          *registry_, "orbit_refusals_total",
          "Calls and streams the server ended with an error, by status code and the rule that "
          "refused them (docs/service.md lists the reasons).")),
      enrollments_family_(AddCounter(
          *registry_, "orbit_enrollments_total",
          "Enroll calls, by outcome: stored, refused, failed (store or server), cancelled (the "
          "client's stream broke).")),
      enrollment_seconds_family_(AddHistogram(
          *registry_, "orbit_enrollment_seconds",
          "Server time from the end of an Enroll stream to its answer (describing uploaded "
          "images, the durable store write, indexing), of enrollments stored.")),
      store_write_seconds_family_(AddHistogram(
          *registry_, "orbit_store_write_seconds",
          "Duration of each committed write to the model store (one transaction, synced to "
          "disk), by operation: enroll, add_views, delete.")),
      change_lag_seconds_family_(AddHistogram(
          *registry_, "orbit_model_change_lag_seconds",
          "With a PostgreSQL store shared by replicas: seconds from the commit of another "
          "replica's change to the change being in this replica's index.")) {
  for (const std::string& name : SessionEngineNames()) {
    frames_[ParseSessionEngine(name)] = &frames_family_.Add({{"engine", name}});
  }
  frame_seconds_[static_cast<int>(FrameInput::kCedd)] =
      &frame_seconds_family_.Add({{"input", "cedd"}}, kFrameBounds);
  frame_seconds_[static_cast<int>(FrameInput::kImage)] =
      &frame_seconds_family_.Add({{"input", "image"}}, kFrameBounds);
  for (const auto& [code, reason] : kRefusalKinds) {
    refusals_[code][static_cast<int>(reason)] =
        &refusals_family_.Add({{"code", std::string(StatusCodeName(code))},
                               {"reason", std::string(RefusalReasonName(reason))}});
  }
  enrollments_[static_cast<int>(EnrollmentOutcome::kStored)] =
      &enrollments_family_.Add({{"outcome", "stored"}});
  enrollments_[static_cast<int>(EnrollmentOutcome::kRefused)] =
      &enrollments_family_.Add({{"outcome", "refused"}});
  enrollments_[static_cast<int>(EnrollmentOutcome::kFailed)] =
      &enrollments_family_.Add({{"outcome", "failed"}});
  enrollments_[static_cast<int>(EnrollmentOutcome::kCancelled)] =
      &enrollments_family_.Add({{"outcome", "cancelled"}});
  enrollment_seconds_ = &enrollment_seconds_family_.Add({}, kEnrollmentBounds);
  store_writes_.enroll =
      &store_write_seconds_family_.Add({{"operation", "enroll"}}, kStoreWriteBounds);
  store_writes_.add_views =
      &store_write_seconds_family_.Add({{"operation", "add_views"}}, kStoreWriteBounds);
  store_writes_.remove =
      &store_write_seconds_family_.Add({{"operation", "delete"}}, kStoreWriteBounds);
  change_lag_seconds_ = &change_lag_seconds_family_.Add({}, kChangeLagBounds);
}

std::vector<std::weak_ptr<prometheus::Collectable>> ServerMetrics::collectables() const {
  return {registry_, gauges_};
}

std::string ServerMetrics::Expose() const {
  std::vector<prometheus::MetricFamily> families = registry_->Collect();
  for (prometheus::MetricFamily& family : gauges_->Collect()) families.push_back(std::move(family));
  std::ostringstream text;
  prometheus::TextSerializer().Serialize(text, families);
  return text.str();
}

FrameMetrics ServerMetrics::ForEngine(v1::Engine engine) {
  FrameMetrics metrics;
  const bool known = engine >= 0 && engine < v1::Engine_ARRAYSIZE && frames_[engine] != nullptr;
  metrics.frames_ = known ? frames_[engine] : &frames_family_.Add({{"engine", "unknown"}});
  metrics.seconds_ = frame_seconds_;
  return metrics;
}

grpc::Status ServerMetrics::Refuse(grpc::Status status, RefusalReason reason) {
  if (!status.ok()) CountRefusal(status.error_code(), reason);
  return status;
}

void ServerMetrics::CountRefusal(grpc::StatusCode code, RefusalReason reason) {
  const int c = static_cast<int>(code), r = static_cast<int>(reason);
  prometheus::Counter* counter = c > 0 && c < kStatusCodes ? refusals_[c][r] : nullptr;
  if (counter == nullptr) {  // a pair outside kRefusalKinds: found (or created) under a lock
    counter = &refusals_family_.Add({{"code", std::string(StatusCodeName(code))},
                                     {"reason", std::string(RefusalReasonName(reason))}});
  }
  counter->Increment();
}

void ServerMetrics::CountEnrollment(EnrollmentOutcome outcome) {
  enrollments_[static_cast<int>(outcome)]->Increment();
}

void ServerMetrics::WatchSessions(const SessionRegistry& sessions) {
  gauges_->Add("orbit_open_sessions", "Session streams open now.", {},
               [&sessions] { return static_cast<double>(sessions.size()); });
}

void ServerMetrics::WatchConnections() {
  gauges_->Add(
      "orbit_connections_refused_total",
      "TCP connections closed as soon as accepted, because they would have used the "
      "descriptors kept free (--descriptor-reserve) or the descriptor table was full.",
      {}, [] { return static_cast<double>(RefusedConnections()); },
      prometheus::MetricType::Counter);
}

void ServerMetrics::WatchIndex(const ModelCatalogue& catalogue) {
  gauges_->Add("orbit_index_objects", "Objects in the index sessions rank.", {},
               [&catalogue] { return static_cast<double>(catalogue.Snapshot()->object_count()); });
  gauges_->Add("orbit_index_views", "Views of every object in the index.", {},
               [&catalogue] { return static_cast<double>(catalogue.Snapshot()->view_count()); });
}

void ServerMetrics::WatchWorkers(const WorkerPool& workers, const WorkerPool& bulk_workers) {
  const std::string name = "orbit_worker_queue_depth";
  const std::string help =
      "Tasks waiting for a worker thread, by pool: workers (Recognize calls, short calls; "
      "--workers) and bulk_workers (image frames, enrollments; --bulk-workers).";
  gauges_->Add(name, help, {{"pool", "workers"}},
               [&workers] { return static_cast<double>(workers.queued()); });
  gauges_->Add(name, help, {{"pool", "bulk_workers"}},
               [&bulk_workers] { return static_cast<double>(bulk_workers.queued()); });
}

}  // namespace orbit::server
