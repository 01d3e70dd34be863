// The Recognition service of proto/orbit/v1/recognition.proto on gRPC's callback API.
//
// Thread-safe; one instance serves every call.
#pragma once

#include <grpcpp/grpcpp.h>

#include "orbit/v1/recognition.grpc.pb.h"
#include "server/access_control.h"
#include "server/calls_per_token.h"
#include "server/session_reactor.h"

namespace orbit::server {

class RecognitionService final : public v1::Recognition::CallbackService {
 public:
  RecognitionService(const SessionEnvironment& environment, const AccessControl& access)
      : env_(environment),
        access_(access),
        recognize_calls_(environment.limits.max_recognize_calls_per_token,
                         "--max-recognize-calls-per-token") {}

  grpc::ServerBidiReactor<v1::SessionRequest, v1::SessionUpdate>* Session(
      grpc::CallbackServerContext* context) override;

  grpc::ServerUnaryReactor* Recognize(grpc::CallbackServerContext* context,
                                      const v1::RecognizeRequest* request,
                                      v1::RecognizeResponse* response) override;

 private:
  const SessionEnvironment env_;
  const AccessControl& access_;
  CallsPerToken recognize_calls_;  // Recognize calls in progress, per token
};

}  // namespace orbit::server
