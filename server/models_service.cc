#include "server/models_service.h"

#include <memory>
#include <mutex>
#include <vector>

#include "api/conversion.h"
#include "server/error_status.h"
#include "server/request_reading.h"
#include "server/unary_call.h"
#include "storage/model_validation.h"
#include "storage/store_error.h"

namespace orbit::server {
namespace {

constexpr int kDefaultPageSize = 100;
constexpr int kMaxPageSize = 1000;
// All the views of one enrollment together (encoded images can be large).
constexpr std::size_t kMaxEnrollmentBytes = 256u << 20;

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

// The id an ObjectRef names. Throws StoreError kNotFound, std::invalid_argument when unset.
ObjectId Resolve(ModelStore& store, const v1::ObjectRef& ref) {
  switch (ref.ref_case()) {
    case v1::ObjectRef::kId:
      if (!store.Get(ref.id())) {
        throw StoreError(StoreError::Code::kNotFound, "no object with id " + std::to_string(ref.id()));
      }
      return ref.id();
    case v1::ObjectRef::kName:
      if (auto found = store.Find(ref.name())) return found->id;
      throw StoreError(StoreError::Code::kNotFound, "no object named '" + ref.name() + "'");
    default:
      throw std::invalid_argument("object: set its id or its name");
  }
}

// Converts wire views to store views, on the worker pool. Views sent as images are described
// by the seed rule of core/view_description.h, which depends on the image alone: the same
// image stores the same numbers whichever object, position or path enrolls it.
grpc::Status ConvertViews(const std::vector<v1::View>& wire, DescriptorVariant variant,
                          const ServerLimits& limits, std::vector<ModelView>* views,
                          std::vector<std::string>* thumbnails) {
  bool any_thumbnail = false;
  for (std::size_t i = 0; i < wire.size(); ++i) {
    ModelView view;
    std::string thumbnail;
    if (grpc::Status s = ToModelView(wire[i], variant, limits, &view, &thumbnail); !s.ok()) {
      return grpc::Status(s.error_code(), "view " + std::to_string(i) + ": " + s.error_message());
    }
    any_thumbnail = any_thumbnail || !thumbnail.empty();
    views->push_back(view);
    thumbnails->push_back(std::move(thumbnail));
  }
  if (!any_thumbnail) thumbnails->clear();
  return grpc::Status::OK;
}

// One Enroll stream: a header, then views, committed when the client closes its side.
class EnrollReactor final : public grpc::ServerReadReactor<v1::EnrollRequest> {
 public:
  EnrollReactor(grpc::CallbackServerContext* context, v1::ObjectInfo* response,
                const ModelsEnvironment& env)
      : context_(context), response_(response), env_(env) {
    if (grpc::Status allowed = env_.access.Authorize(*context, Role::kAdmin); !allowed.ok()) {
      Finish(allowed);
      return;
    }
    StartRead(&request_);
  }

  void OnReadDone(bool ok) override {
    if (!ok) {
      if (context_->IsCancelled()) {
        Finish({grpc::StatusCode::CANCELLED, "the enrollment stream broke; nothing was stored"});
      } else {
        env_.bulk_pool.Post([this] { Finish(Commit()); });
      }
      return;
    }
    if (grpc::Status s = Accept(); !s.ok()) {
      Finish(s);
      return;
    }
    StartRead(&request_);
  }

  void OnDone() override { delete this; }

 private:
  grpc::Status Accept() {
    if (request_.kind_case() == v1::EnrollRequest::kHeader) {
      if (have_header_) return InvalidArgument("the header may be sent only once");
      const v1::EnrollHeader& header = request_.header();
      if (auto s = CheckVariant(header.variant(), env_.catalogue.variant(), "header.variant");
          !s.ok()) {
        return s;
      }
      try {
        ValidateObjectName(header.name());
        ValidateMetadata(header.metadata_json().empty() ? "{}" : header.metadata_json());
      } catch (const std::exception& e) {
        return StatusFromException(e);
      }
      header_ = header;
      have_header_ = true;
      return grpc::Status::OK;
    }
    if (request_.kind_case() != v1::EnrollRequest::kView) {
      return InvalidArgument("empty request: set header or view");
    }
    if (!have_header_) return InvalidArgument("the first message must be the header");
    if (views_.size() >= kMaxViewsPerObject) {
      return {grpc::StatusCode::RESOURCE_EXHAUSTED,
              "more than " + std::to_string(kMaxViewsPerObject) + " views for one object"};
    }
    bytes_ += request_.view().ByteSizeLong();
    if (bytes_ > kMaxEnrollmentBytes) {
      return {grpc::StatusCode::RESOURCE_EXHAUSTED, "enrollment larger than 256 MiB"};
    }
    views_.push_back(std::move(*request_.mutable_view()));
    return grpc::Status::OK;
  }

  // On the worker pool, after the client closed its side.
  grpc::Status Commit() {
    if (!have_header_) return InvalidArgument("no header: nothing to enroll");
    if (views_.empty()) return InvalidArgument("no views: an object needs at least one");
    Enrollment enrollment;
    enrollment.name = header_.name();
    enrollment.variant = env_.catalogue.variant();
    enrollment.metadata = header_.metadata_json().empty() ? "{}" : header_.metadata_json();
    if (grpc::Status s =
            ConvertViews(views_, enrollment.variant, env_.limits, &enrollment.views,
                         &enrollment.thumbnails);
        !s.ok()) {
      return s;
    }
    try {
      *response_ = ToObjectInfo(env_.catalogue.Enroll(enrollment));
    } catch (const std::exception& e) {
      return StatusFromException(e);
    }
    return grpc::Status::OK;
  }

  grpc::CallbackServerContext* const context_;
  v1::ObjectInfo* const response_;
  const ModelsEnvironment& env_;
  v1::EnrollRequest request_;
  v1::EnrollHeader header_;
  bool have_header_ = false;
  std::vector<v1::View> views_;
  std::size_t bytes_ = 0;
};

}  // namespace

grpc::ServerReadReactor<v1::EnrollRequest>* ModelsService::Enroll(
    grpc::CallbackServerContext* context, v1::ObjectInfo* response) {
  return new EnrollReactor(context, response, env_);
}

grpc::ServerUnaryReactor* ModelsService::AddViews(grpc::CallbackServerContext* context,
                                                  const v1::AddViewsRequest* request,
                                                  v1::ObjectInfo* response) {
  return RunUnaryCall(context, env_.access, Role::kAdmin, env_.bulk_pool, [this, request, response] {
    const ObjectId id = Resolve(env_.catalogue.store(), request->object());
    if (request->views().empty()) return InvalidArgument("views is empty");
    std::vector<ModelView> views;
    std::vector<std::string> thumbnails;
    const std::vector<v1::View> wire(request->views().begin(), request->views().end());
    if (grpc::Status s =
            ConvertViews(wire, env_.catalogue.variant(), env_.limits, &views, &thumbnails);
        !s.ok()) {
      return s;
    }
    *response = ToObjectInfo(env_.catalogue.AddViews(id, views, thumbnails));
    return grpc::Status::OK;
  });
}

grpc::ServerUnaryReactor* ModelsService::ListObjects(grpc::CallbackServerContext* context,
                                                     const v1::ListObjectsRequest* request,
                                                     v1::ListObjectsResponse* response) {
  return RunUnaryCall(context, env_.access, Role::kRecognize, env_.pool, [this, request, response] {
    ListRequest page;
    page.limit = request->page_size() == 0 ? kDefaultPageSize : request->page_size();
    if (page.limit < 1 || page.limit > kMaxPageSize) return InvalidArgument("page_size must be 1..1000");
    if (!request->page_token().empty()) {
      std::size_t used = 0;
      try {
        page.after_id = std::stoll(request->page_token(), &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != request->page_token().size() || page.after_id < 0) {
        return InvalidArgument("page_token is not one this server gave");
      }
    }
    const std::vector<ObjectSummary> objects = env_.catalogue.store().List(page);
    for (const ObjectSummary& summary : objects) *response->add_objects() = ToObjectInfo(summary);
    if (static_cast<int>(objects.size()) == page.limit) {
      response->set_next_page_token(std::to_string(objects.back().id));
    }
    return grpc::Status::OK;
  });
}

grpc::ServerUnaryReactor* ModelsService::GetObject(grpc::CallbackServerContext* context,
                                                   const v1::GetObjectRequest* request,
                                                   v1::GetObjectResponse* response) {
  return RunUnaryCall(context, env_.access, Role::kRecognize, env_.pool, [this, request, response] {
    const ObjectId id = Resolve(env_.catalogue.store(), request->object());
    const std::optional<StoredObject> object = env_.catalogue.store().Get(id);
    if (!object) return grpc::Status(grpc::StatusCode::NOT_FOUND, "object deleted meanwhile");
    *response->mutable_object() = ToObjectInfo(object->summary);
    if (request->include_views()) {
      for (std::size_t i = 0; i < object->views.size(); ++i) {
        const std::string none;
        const std::string& thumbnail = request->include_thumbnails() && i < object->thumbnails.size()
                                           ? object->thumbnails[i]
                                           : none;
        *response->add_views() = ToProtoView(object->views[i], thumbnail);
      }
    }
    return grpc::Status::OK;
  });
}

grpc::ServerUnaryReactor* ModelsService::DeleteObject(grpc::CallbackServerContext* context,
                                                      const v1::DeleteObjectRequest* request,
                                                      v1::DeleteObjectResponse* response) {
  return RunUnaryCall(context, env_.access, Role::kAdmin, env_.pool, [this, request, response] {
    const ObjectId id = Resolve(env_.catalogue.store(), request->object());
    *response->mutable_deleted() = ToObjectInfo(env_.catalogue.Delete(id));
    return grpc::Status::OK;
  });
}

grpc::ServerUnaryReactor* ModelsService::ServerInfo(grpc::CallbackServerContext* context,
                                                    const v1::ServerInfoRequest* /*request*/,
                                                    v1::ServerInfoResponse* response) {
  return RunUnaryCall(context, env_.access, Role::kRecognize, env_.pool, [this, response] {
    const std::shared_ptr<const ViewIndexSnapshot> index = env_.catalogue.Snapshot();
    response->set_version(env_.version);
    response->set_variant(ToProtoVariant(env_.catalogue.variant()));
    response->set_object_count(static_cast<std::int64_t>(index->object_count()));
    response->set_view_count(static_cast<std::int64_t>(index->view_count()));
    *response->mutable_session_defaults() = DescribeSettings(env_.defaults, env_.catalogue.variant());
    v1::Limits* limits = response->mutable_limits();
    limits->set_max_sessions(env_.limits.max_sessions);
    limits->set_max_frames_per_second(env_.limits.max_frames_per_second);
    limits->set_max_window(env_.limits.max_window);
    limits->set_max_message_bytes(env_.limits.max_message_bytes);
    limits->set_max_views_per_object(static_cast<int>(kMaxViewsPerObject));
    limits->set_idle_timeout_seconds(env_.limits.idle_timeout_seconds);
    limits->set_max_image_pixels(env_.limits.max_image_pixels);
    limits->set_max_hmm_cells(env_.limits.max_hmm_cells);
    return grpc::Status::OK;
  });
}

}  // namespace orbit::server
