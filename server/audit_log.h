// AuditLog: one JSON line per administrative call and per refused authentication
// (docs/service.md, "Audit log"), so that every change to the models and every attempt with a
// wrong token can be attributed: when, by which token's name, from which peer, which call, on
// which object, with what outcome.
//
//   {"time":"2026-11-27T07:50:01.123Z","call":"Models/DeleteObject","token":"ops-laptop",
//    "peer":"ipv4:10.0.0.7:51234","object":"mug","outcome":"OK"}
//
// Lines go to a file (appended, flushed per line) or to stderr. Thread-safe.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include <grpcpp/grpcpp.h>

#include "core/base/mutex.h"

namespace orbit::server {

struct AuditEvent {
  std::string_view call = {};    // "Models/Enroll"
  std::string_view token = {};   // the grant's name; "" when the call carried no known token
  std::string_view peer = {};    // gRPC's peer string, e.g. "ipv4:127.0.0.1:51234"
  std::string_view object = {};  // the object's name or id; "" when the call names none
  grpc::StatusCode outcome = grpc::StatusCode::OK;
  std::string_view message = {};  // the refusal's message; "" for OK
};

class AuditLog {
 public:
  // "-": stderr; else the file, created (mode 0600) or appended to. Throws std::runtime_error
  // naming the file when it cannot be opened.
  explicit AuditLog(const std::string& destination);

  void Record(const AuditEvent& event) ABSL_LOCKS_EXCLUDED(mutex_);

 private:
  Mutex mutex_;
  std::ofstream file_ ABSL_GUARDED_BY(mutex_);
  bool to_stderr_ = false;
};

}  // namespace orbit::server
