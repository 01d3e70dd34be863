// The Models service of proto/orbit/v1/models.proto on gRPC's callback API: enrollment and
// management of objects while sessions run.
//
// Thread-safe; one instance serves every call.
#pragma once

#include <string>

#include <grpcpp/grpcpp.h>

#include "orbit/v1/models.grpc.pb.h"
#include "server/access_control.h"
#include "server/audit_log.h"
#include "server/model_catalogue.h"
#include "server/rejection_calibrator.h"
#include "server/server_metrics.h"
#include "server/serving_gate.h"
#include "server/session_registry.h"
#include "server/session_settings.h"
#include "server/worker_pool.h"

namespace orbit::server {

struct ModelsEnvironment {
  ModelCatalogue& catalogue;
  WorkerPool& pool;       // short calls: list, get, delete, server info
  WorkerPool& bulk_pool;  // enrollments and added views: describing images, the store's fsync
  const AccessControl& access;
  const ServerLimits& limits;
  const SessionSettings& defaults;
  std::string version;
  ServerMetrics& metrics;        // enrollments and refusals are counted here
  const ServingGate& gate;       // closed until the index is loaded: every call refused UNAVAILABLE
  SessionRegistry& enrollments;  // the open Enroll streams (--max-enrollments)
  AuditLog& audit;               // every administrative call's outcome
  RejectionCalibrator& calibrator;  // the calibrated rule's, for ServerInfo's estimate
};

class ModelsService final : public v1::Models::CallbackService {
 public:
  explicit ModelsService(ModelsEnvironment environment) : env_(std::move(environment)) {}

  grpc::ServerReadReactor<v1::EnrollRequest>* Enroll(grpc::CallbackServerContext* context,
                                                     v1::ObjectInfo* response) override;
  grpc::ServerUnaryReactor* AddViews(grpc::CallbackServerContext* context,
                                     const v1::AddViewsRequest* request,
                                     v1::ObjectInfo* response) override;
  grpc::ServerUnaryReactor* ListObjects(grpc::CallbackServerContext* context,
                                        const v1::ListObjectsRequest* request,
                                        v1::ListObjectsResponse* response) override;
  grpc::ServerUnaryReactor* GetObject(grpc::CallbackServerContext* context,
                                      const v1::GetObjectRequest* request,
                                      v1::GetObjectResponse* response) override;
  grpc::ServerUnaryReactor* DeleteObject(grpc::CallbackServerContext* context,
                                         const v1::DeleteObjectRequest* request,
                                         v1::DeleteObjectResponse* response) override;
  grpc::ServerUnaryReactor* ServerInfo(grpc::CallbackServerContext* context,
                                       const v1::ServerInfoRequest* request,
                                       v1::ServerInfoResponse* response) override;

 private:
  ModelsEnvironment env_;
};

}  // namespace orbit::server
