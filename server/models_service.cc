#include "server/models_service.h"

#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "api/conversion.h"
#include "api/engines/conversion.h"
#include "core/decision/enrollment_feedback.h"
#include "server/enrollment_stream.h"
#include "server/error_status.h"
#include "server/request_reading.h"
#include "server/server_metrics.h"
#include "server/unary_call.h"
#include "storage/model_validation.h"
#include "storage/store_error.h"

namespace orbit::server {
namespace {

constexpr int kDefaultPageSize = 100;
constexpr int kMaxPageSize = 1000;
// A GetObject response with views stays under a default client's 4 MiB receive limit
// (models.proto, GetObjectResponse); the rest is in the next page.
constexpr std::size_t kMaxObjectResponseBytes = 3u << 20;
constexpr std::size_t kViewFieldOverhead = 8;  // a repeated field's tag and length

// The enrollment report of object `summary.id` as the index holds it now
// (core/decision/enrollment_feedback.h); left unset when another call deleted it meanwhile.
void AddEnrollmentReport(ModelCatalogue& catalogue, const ObjectSummary& summary,
                         v1::ObjectInfo* info) {
  const std::shared_ptr<const ViewIndexSnapshot> index = catalogue.Snapshot();
  const IndexedObject* object = index->Find(summary.id);
  if (object == nullptr) return;
  *info->mutable_report() = ToEnrollmentReport(AssessEnrollment(object->model(), *index), *index);
}

v1::ObjectInfo ToObjectInfo(const ObjectSummary& summary) {
  v1::ObjectInfo info;
  info.set_id(summary.id);
  info.set_name(summary.name);
  info.set_variant(ToProtoVariant(summary.variant));
  info.set_view_count(summary.view_count);
  info.set_created_at(summary.created_at);
  info.set_updated_at(summary.updated_at);
  info.set_metadata_json(summary.metadata);
  return info;
}

// An ObjectRef as the audit log names it: the name, or "id N".
std::string ObjectRefText(const v1::ObjectRef& ref) {
  return ref.ref_case() == v1::ObjectRef::kName ? ref.name() : "id " + std::to_string(ref.id());
}

// The id an ObjectRef names. Throws StoreError kNotFound, std::invalid_argument when unset.
ObjectId Resolve(ModelStore& store, const v1::ObjectRef& ref) {
  switch (ref.ref_case()) {
    case v1::ObjectRef::kId:
      if (!store.Get(ref.id())) {
        throw ObjectNotFound(ref.id());
      }
      return ref.id();
    case v1::ObjectRef::kName:
      if (auto found = store.Find(ref.name())) return found->id;
      throw StoreError(StoreError::Code::kNotFound, "no object named '" + ref.name() + "'");
    default: throw std::invalid_argument("object: set its id or its name");
  }
}

// One Enroll stream: a header, then views, committed when the client closes its side. Registered
// with the enrollments' registry (server/session_registry.h) from its first read to its commit:
// held to --max-enrollments at once, and cancelled after --enrollment-idle-timeout without a
// message or at shutdown (docs/design.md#stream-limits).
class EnrollReactor final : public grpc::ServerReadReactor<v1::EnrollRequest>,
                            public RegisteredSession {
 public:
  EnrollReactor(grpc::CallbackServerContext* context, v1::ObjectInfo* response,
                const ModelsEnvironment& env)
      : context_(context), response_(response), env_(env) {
    if (grpc::Status allowed =
            env_.access.Authorize(*context, Role::kAdmin, "Models/Enroll", &token_);
        !allowed.ok()) {
      Answer(allowed, RefusalReason::kAccess);
      return;
    }
    if (grpc::Status admitted = env_.gate.Admit(); !admitted.ok()) {
      Answer(admitted, RefusalReason::kStarting);
      return;
    }
    // OnDone leaves the registry (Remove ignores a stream never admitted). The registry may close
    // the stream as soon as it is admitted, before the first read starts: the cancellation then
    // completes that read.
    if (grpc::Status admitted = env_.enrollments.Add(this, token_); !admitted.ok()) {
      Answer(admitted, admitted.error_code() == grpc::StatusCode::UNAVAILABLE
                           ? RefusalReason::kShuttingDown
                           : RefusalReason::kMaxEnrollments);
      return;
    }
    StartRead(&request_);
  }

  void OnReadDone(bool ok) override {
    std::optional<grpc::Status> closing;
    RefusalReason closing_reason = RefusalReason::kInternal;
    {
      MutexLock lock(&mutex_);
      closing = closing_;
      closing_reason = closing_reason_;
      if (ok && !closing) last_activity_ = Clock::now().time_since_epoch().count();
    }
    if (closing) {
      // Closed by the registry (idle, revoked token, shutdown): the client sees CANCELLED.
      Answer(*closing, closing_reason);
      return;
    }
    if (!ok) {
      if (context_->IsCancelled()) {
        const grpc::Status broke(grpc::StatusCode::CANCELLED,
                                 "the enrollment stream broke; nothing was stored");
        Audit(broke);
        env_.metrics.CountEnrollment(EnrollmentOutcome::kCancelled);
        Finish(broke);
      } else {
        stream_ended_ = Clock::now();
        {
          MutexLock lock(&mutex_);
          committing_ = true;  // the registry no longer closes it: the commit answers
        }
        env_.bulk_pool.Post(
            {.run =
                 [this] {
                   grpc::Status status;
                   RefusalReason reason;
                   try {
                     status = Commit();
                     reason = ReasonOfCheck(status, RefusalReason::kImageBudget);
                   } catch (const std::exception& e) {  // from the catalogue: a duplicate
                                                        // name, the store
                     status = StatusFromException(e);
                     reason = RefusalReasonOf(e);
                   }
                   Answer(status, reason);
                 },
             // Nothing was stored: the client may enroll again on another replica.
             .abandon = [this] { Answer(ShuttingDown(), RefusalReason::kShuttingDown); }});
      }
      return;
    }
    if (grpc::Status s = stream_.Accept(&request_); !s.ok()) {
      Answer(s, ReasonOfCheck(s, RefusalReason::kRequestSize));
      return;
    }
    StartRead(&request_);
  }

  // From the registry, with its lock held: cancels the call unless the commit has begun.
  void Close(const grpc::Status& status) override {
    {
      MutexLock lock(&mutex_);
      if (committing_ || closing_) return;
      closing_ = status;
      closing_reason_ =
          status.error_code() == grpc::StatusCode::DEADLINE_EXCEEDED ? RefusalReason::kIdleTimeout
          : status.error_code() == grpc::StatusCode::UNAUTHENTICATED ? RefusalReason::kAccess
                                                                     : RefusalReason::kShuttingDown;
    }
    context_->TryCancel();
  }

  std::chrono::steady_clock::time_point last_activity() const override {
    return Clock::time_point(Clock::duration(last_activity_.load()));
  }

  void OnDone() override {
    env_.enrollments.Remove(this);
    delete this;
  }

 private:
  using Clock = std::chrono::steady_clock;

  // Ends the call with `status`, counting the enrollment by its outcome: the time since the
  // stream ended when it was stored, the refusal under `reason` when it was not.
  void Answer(const grpc::Status& status, RefusalReason reason) {
    if (reason != RefusalReason::kAccess) Audit(status);  // Authorize recorded its refusal
    ServerMetrics& metrics = env_.metrics;
    if (status.ok()) {
      metrics.CountEnrollment(EnrollmentOutcome::kStored);
      metrics.enrollment_seconds().Observe(
          std::chrono::duration<double>(Clock::now() - stream_ended_).count());
    } else {
      metrics.CountRefusal(status.error_code(), reason);
      metrics.CountEnrollment(reason == RefusalReason::kStore || reason == RefusalReason::kInternal
                                  ? EnrollmentOutcome::kFailed
                                  : EnrollmentOutcome::kRefused);
    }
    Finish(status);
  }

  void Audit(const grpc::Status& status) {
    const std::string peer = context_->peer();
    env_.audit.Record({.call = "Models/Enroll",
                       .token = token_,
                       .peer = peer,
                       .object = stream_.name(),
                       .outcome = status.error_code(),
                       .message = status.error_message()});
  }

  // On the worker pool, after the client closed its side. Throws what the catalogue's Enroll
  // throws.
  grpc::Status Commit() {
    Enrollment enrollment;
    if (grpc::Status s = stream_.ToEnrollment(env_.limits, &enrollment); !s.ok()) return s;
    const ObjectSummary summary = env_.catalogue.Enroll(enrollment);
    *response_ = ToObjectInfo(summary);
    AddEnrollmentReport(env_.catalogue, summary, response_);
    return grpc::Status::OK;
  }

  grpc::CallbackServerContext* const context_;
  v1::ObjectInfo* const response_;
  const ModelsEnvironment& env_;
  v1::EnrollRequest request_;
  std::string token_;               // the caller's token's name, once authorized
  Clock::time_point stream_ended_;  // when the client closed its side
  EnrollmentStream stream_{env_.catalogue.variant(), env_.limits.max_enrollment_bytes};
  std::atomic<Clock::rep> last_activity_{Clock::now().time_since_epoch().count()};
  // Taken after the registry's lock (it calls Close with that lock held), never before it.
  Mutex mutex_ ABSL_ACQUIRED_AFTER(env_.enrollments.mutex());
  bool committing_ ABSL_GUARDED_BY(mutex_) = false;
  std::optional<grpc::Status> closing_ ABSL_GUARDED_BY(mutex_);
  RefusalReason closing_reason_ ABSL_GUARDED_BY(mutex_) = RefusalReason::kInternal;
};

}  // namespace

grpc::ServerReadReactor<v1::EnrollRequest>* ModelsService::Enroll(
    grpc::CallbackServerContext* context, v1::ObjectInfo* response) {
  return new EnrollReactor(context, response, env_);
}

grpc::ServerUnaryReactor* ModelsService::AddViews(grpc::CallbackServerContext* context,
                                                  const v1::AddViewsRequest* request,
                                                  v1::ObjectInfo* response) {
  return RunUnaryCall(
      context, env_.access,
      {.name = "Models/AddViews",
       .role = Role::kAdmin,
       .pool = env_.bulk_pool,
       .audit = &env_.audit,
       .object = ObjectRefText(request->object())},
      env_.gate, env_.metrics, [this, request, response] {
        const ObjectId id = Resolve(env_.catalogue.store(), request->object());
        if (request->views().empty()) {
          return env_.metrics.Refuse(InvalidArgument("views is empty"),
                                     RefusalReason::kInvalidField);
        }
        std::vector<ModelView> views;
        std::vector<std::string> thumbnails;
        const std::vector<v1::View> wire(request->views().begin(), request->views().end());
        if (grpc::Status s =
                ToModelViews(wire, env_.catalogue.variant(), env_.limits, &views, &thumbnails);
            !s.ok()) {
          return env_.metrics.Refuse(s, ReasonOfCheck(s, RefusalReason::kImageBudget));
        }
        const ObjectSummary summary = env_.catalogue.AddViews(id, views, thumbnails);
        *response = ToObjectInfo(summary);
        AddEnrollmentReport(env_.catalogue, summary, response);
        return grpc::Status::OK;
      });
}

grpc::ServerUnaryReactor* ModelsService::ListObjects(grpc::CallbackServerContext* context,
                                                     const v1::ListObjectsRequest* request,
                                                     v1::ListObjectsResponse* response) {
  return RunUnaryCall(
      context, env_.access,
      {.name = "Models/ListObjects", .role = Role::kRecognize, .pool = env_.pool}, env_.gate,
      env_.metrics, [this, request, response] {
        ListRequest page;
        page.limit = request->page_size() == 0 ? kDefaultPageSize : request->page_size();
        if (page.limit < 1 || page.limit > kMaxPageSize) {
          return env_.metrics.Refuse(InvalidArgument("page_size must be 1..1000"),
                                     RefusalReason::kInvalidField);
        }
        if (!request->page_token().empty()) {
          std::size_t used = 0;
          try {
            page.after_id = std::stoll(request->page_token(), &used);
          } catch (const std::exception&) {
            used = 0;
          }
          if (used != request->page_token().size() || page.after_id < 0) {
            return env_.metrics.Refuse(InvalidArgument("page_token is not one this server gave"),
                                       RefusalReason::kInvalidField);
          }
        }
        const std::vector<ObjectSummary> objects = env_.catalogue.store().List(page);
        for (const ObjectSummary& summary : objects)
          *response->add_objects() = ToObjectInfo(summary);
        if (static_cast<int>(objects.size()) == page.limit) {
          response->set_next_page_token(std::to_string(objects.back().id));
        }
        return grpc::Status::OK;
      });
}

grpc::ServerUnaryReactor* ModelsService::GetObject(grpc::CallbackServerContext* context,
                                                   const v1::GetObjectRequest* request,
                                                   v1::GetObjectResponse* response) {
  return RunUnaryCall(
      context, env_.access,
      {.name = "Models/GetObject", .role = Role::kRecognize, .pool = env_.pool}, env_.gate,
      env_.metrics, [this, request, response] {
        const ObjectId id = Resolve(env_.catalogue.store(), request->object());
        const std::optional<StoredObject> object = env_.catalogue.store().Get(id);
        if (!object) {
          return env_.metrics.Refuse({grpc::StatusCode::NOT_FOUND, "object deleted meanwhile"},
                                     RefusalReason::kUnknownObject);
        }
        *response->mutable_object() = ToObjectInfo(object->summary);
        if (!request->include_views()) return grpc::Status::OK;
        const int views = static_cast<int>(object->views.size());
        if (request->view_offset() < 0 || request->view_offset() > views) {
          return env_.metrics.Refuse(
              InvalidArgument("view_offset is " + std::to_string(request->view_offset()) +
                              ", expected 0.." + std::to_string(views)),
              RefusalReason::kInvalidField);
        }
        std::size_t bytes = response->ByteSizeLong();
        for (int i = request->view_offset(); i < views; ++i) {
          const std::string none;
          const std::string& thumbnail =
              request->include_thumbnails() && i < static_cast<int>(object->thumbnails.size())
                  ? object->thumbnails[i]
                  : none;
          v1::View view = ToProtoView(object->views[i], object->summary.variant, thumbnail);
          bytes += view.ByteSizeLong() + kViewFieldOverhead;
          if (bytes > kMaxObjectResponseBytes && response->views_size() > 0) {
            response->set_next_view_offset(i);
            break;
          }
          *response->add_views() = std::move(view);
        }
        return grpc::Status::OK;
      });
}

grpc::ServerUnaryReactor* ModelsService::DeleteObject(grpc::CallbackServerContext* context,
                                                      const v1::DeleteObjectRequest* request,
                                                      v1::DeleteObjectResponse* response) {
  return RunUnaryCall(context, env_.access,
                      {.name = "Models/DeleteObject",
                       .role = Role::kAdmin,
                       .pool = env_.pool,
                       .audit = &env_.audit,
                       .object = ObjectRefText(request->object())},
                      env_.gate, env_.metrics, [this, request, response] {
                        const ObjectId id = Resolve(env_.catalogue.store(), request->object());
                        *response->mutable_deleted() = ToObjectInfo(env_.catalogue.Delete(id));
                        return grpc::Status::OK;
                      });
}

namespace {

// What the calibration says of the default rule: the shares of its simulated unknown and known
// windows of the default length that the default rule accepts.
v1::RuleEstimate EstimateRule(const RejectionCalibration& calibration,
                              const EngineOptions& defaults) {
  v1::RuleEstimate estimate;
  if (!calibration.calibrated()) return estimate;
  const int frames = std::min(defaults.window, kCalibratedWindowLengths);
  const double rule_threshold =
      calibration.Threshold(frames, defaults.false_accept_rate, defaults.known_accept_rate);
  const double ceiling = calibration.KnownCeiling(frames);
  const double threshold = std::min(rule_threshold, ceiling);
  estimate.set_objects(calibration.sampled_objects());
  estimate.set_frames(frames);
  estimate.set_unknown_accepted(calibration.NullShare(threshold, frames));
  estimate.set_known_accepted(calibration.KnownAcceptRate(threshold, frames));
  estimate.set_held_by_known_ceiling(ceiling < rule_threshold);
  return estimate;
}

}  // namespace

grpc::ServerUnaryReactor* ModelsService::ServerInfo(grpc::CallbackServerContext* context,
                                                    const v1::ServerInfoRequest* /*request*/,
                                                    v1::ServerInfoResponse* response) {
  return RunUnaryCall(
      context, env_.access,
      {.name = "Models/ServerInfo", .role = Role::kRecognize, .pool = env_.pool}, env_.gate,
      env_.metrics, [this, response] {
        const std::shared_ptr<const ViewIndexSnapshot> index = env_.catalogue.Snapshot();
        response->set_version(env_.version);
        response->set_variant(ToProtoVariant(env_.catalogue.variant()));
        response->set_object_count(static_cast<std::int64_t>(index->object_count()));
        response->set_view_count(static_cast<std::int64_t>(index->view_count()));
        *response->mutable_session_defaults() =
            DescribeSettings(env_.defaults, env_.catalogue.variant());
        v1::Limits* limits = response->mutable_limits();
        limits->set_max_sessions(env_.limits.max_sessions);
        limits->set_max_frames_per_second(env_.limits.max_frames_per_second);
        limits->set_max_window(env_.limits.max_window);
        limits->set_max_message_bytes(env_.limits.max_message_bytes);
        limits->set_max_queued_calls(env_.limits.max_queued_calls);
        limits->set_max_enrollments(env_.limits.max_enrollments);
        limits->set_max_enrollment_bytes(env_.limits.max_enrollment_bytes);
        limits->set_enrollment_idle_timeout_seconds(env_.limits.enrollment_idle_timeout_seconds);
        limits->set_max_sessions_per_token(env_.limits.max_sessions_per_token);
        limits->set_max_recognize_calls_per_token(env_.limits.max_recognize_calls_per_token);
        limits->set_max_views_per_object(static_cast<int>(kMaxViewsPerObject));
        limits->set_idle_timeout_seconds(env_.limits.idle_timeout_seconds);
        limits->set_max_image_pixels(env_.limits.max_image_pixels);
        limits->set_max_hmm_cells(env_.limits.max_hmm_cells);
        *response->mutable_rule_estimate() =
            EstimateRule(*env_.calibrator.For(index), env_.defaults.options);
        return grpc::Status::OK;
      });
}

}  // namespace orbit::server
