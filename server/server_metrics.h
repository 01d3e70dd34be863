// ServerMetrics: what `orbit serve` measures about itself, in Prometheus' data model with
// Debian's prometheus-cpp, exposed at --metrics-listen (server/metrics_endpoint.h; every metric
// is described in docs/service.md, "Metrics"). The metrics' names, help texts, labels and
// buckets are written here once; the children the hot paths update are resolved when the server
// starts, so that a frame costs a counter increment and a histogram observation
// (bench/metrics_bench.cc measures it). The gauges (open sessions, index size, queue depths) are
// read from the server's own state at each scrape, so no hot path updates them.
//
// Thread-safe.
#pragma once

#include <grpcpp/grpcpp.h>

#include <prometheus/collectable.h>
#include <prometheus/counter.h>
#include <prometheus/family.h>
#include <prometheus/histogram.h>
#include <prometheus/registry.h>

#include <array>
#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "orbit/v1/recognition.pb.h"
#include "server/refusal_reason.h"

namespace orbit::server {

class ModelCatalogue;
class SessionRegistry;
class WorkerPool;

// How a frame reached the server (the `input` label): Frame.cedd or Frame.image.
enum class FrameInput { kCedd, kImage };

// What a processed frame updates, for one engine: resolved once per session (or Recognize
// call), then used for each of its frames.
class FrameMetrics {
 public:
  // Updates nothing; REQUIRES assignment from ServerMetrics::ForEngine before Record.
  FrameMetrics() = default;

  // One frame processed in `spent` on the server (from its read to its update being ready): an
  // atomic add to the engine's frame counter and one histogram observation (prometheus-cpp
  // takes the histogram's mutex); no allocation, no label lookup.
  void Record(FrameInput input, std::chrono::steady_clock::duration spent) const noexcept {
    frames_->Increment();
    seconds_[static_cast<int>(input)]->Observe(std::chrono::duration<double>(spent).count());
  }

 private:
  friend class ServerMetrics;
  prometheus::Counter* frames_ = nullptr;
  std::array<prometheus::Histogram*, 2> seconds_{};  // by FrameInput
};

// How an Enroll call ended (the `outcome` label).
enum class EnrollmentOutcome {
  kStored,     // stored: answered OK; the object is durable and indexed
  kRefused,    // refused: a bad request, a limit or a duplicate name (orbit_refusals_total says
               // which)
  kFailed,     // failed: the store or the server failed (reason store or internal)
  kCancelled,  // cancelled: the client's stream broke before it closed; nothing was stored
};

// Where ModelCatalogue reports how long each committed store write took.
struct StoreWriteHistograms {
  prometheus::Histogram* enroll = nullptr;     // Enroll: the object and its views
  prometheus::Histogram* add_views = nullptr;  // AddViews
  prometheus::Histogram* remove = nullptr;     // Delete
};

class ServerMetrics {
 public:
  // Registers every metric, each labelled child at zero.
  ServerMetrics();

  ServerMetrics(const ServerMetrics&) = delete;
  ServerMetrics& operator=(const ServerMetrics&) = delete;

  // What a scrape collects, in order: the counters and histograms, then the gauges read from
  // the watched state. Each stays valid while this object lives (an exposer holds them weakly).
  std::vector<std::weak_ptr<prometheus::Collectable>> collectables() const;
  // Every metric in the text exposition format 0.0.4, as a scrape reads it.
  std::string Expose() const;

  // The frame metrics of sessions running `engine`. REQUIRES: a resolved engine (not
  // ENGINE_UNSPECIFIED); any other value is counted under engine="unknown".
  FrameMetrics ForEngine(v1::Engine engine);

  // Counts a refusal with `status`'s code and `reason`, and returns `status` (so that a refusal
  // reads `return metrics.Refuse(status, reason);`). Nothing is counted for an OK status.
  grpc::Status Refuse(grpc::Status status, RefusalReason reason);
  void CountRefusal(grpc::StatusCode code, RefusalReason reason);

  void CountEnrollment(EnrollmentOutcome outcome);
  // Seconds from the end of an Enroll stream to its answer, for enrollments stored.
  prometheus::Histogram& enrollment_seconds() { return *enrollment_seconds_; }

  StoreWriteHistograms store_writes() const { return store_writes_; }

  // Seconds from the commit of another replica's change (the change log's committed_at) to its
  // object being in this replica's index (server/model_change_follower.h).
  prometheus::Histogram& change_lag_seconds() { return *change_lag_seconds_; }

  // Gauges read at each scrape: the open sessions, the index's size, the tasks waiting for each
  // pool's workers. Each object must outlive every later scrape. Until watched, a gauge is not
  // exposed.
  void WatchSessions(const SessionRegistry& sessions);
  void WatchIndex(const ModelCatalogue& catalogue);
  void WatchWorkers(const WorkerPool& workers, const WorkerPool& bulk_workers);
  // The connections refused at accept (server/connection_admission.h), a counter.
  void WatchConnections();

 private:
  static constexpr int kStatusCodes = 17;  // OK .. UNAUTHENTICATED

  class WatchedGauges;

  std::shared_ptr<prometheus::Registry> registry_;
  std::shared_ptr<WatchedGauges> gauges_;
  prometheus::Family<prometheus::Counter>& frames_family_;
  prometheus::Family<prometheus::Histogram>& frame_seconds_family_;
  prometheus::Family<prometheus::Counter>& refusals_family_;
  prometheus::Family<prometheus::Counter>& enrollments_family_;
  prometheus::Family<prometheus::Histogram>& enrollment_seconds_family_;
  prometheus::Family<prometheus::Histogram>& store_write_seconds_family_;
  prometheus::Family<prometheus::Histogram>& change_lag_seconds_family_;
  std::array<prometheus::Counter*, v1::Engine_ARRAYSIZE> frames_{};
  std::array<prometheus::Histogram*, 2> frame_seconds_{};
  // refusals_[code][reason], for the pairs of kRefusalKinds; others are found when counted.
  std::array<std::array<prometheus::Counter*, kRefusalReasonCount>, kStatusCodes> refusals_{};
  std::array<prometheus::Counter*, 4> enrollments_{};  // by EnrollmentOutcome
  prometheus::Histogram* enrollment_seconds_;
  StoreWriteHistograms store_writes_;
  prometheus::Histogram* change_lag_seconds_;
};

}  // namespace orbit::server
