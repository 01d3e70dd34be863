// A well-behaved device beside an attack: one session of descriptor frames, one after another,
// each answer timed, so that a test of a hostile client can check that the others are unharmed
// (tests/server/hostile_clients_test.cc).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <grpcpp/grpcpp.h>

#include "orbit/v1/recognition.grpc.pb.h"
#include "tests/support/synthetic_descriptor.h"

namespace orbit::testing {

class WellBehavedSession {
 public:
  using Clock = std::chrono::steady_clock;

  explicit WellBehavedSession(const std::shared_ptr<grpc::Channel>& channel,
                              const std::string& token = "")
      : stub_(v1::Recognition::NewStub(channel)) {
    if (!token.empty()) context_.AddMetadata("authorization", "Bearer " + token);
    stream_ = stub_->Session(&context_);
    v1::SessionRequest open;
    open.mutable_open();
    stream_->Write(open);
  }

  // The 99th percentile of `frames` frames' round trips (the server's answer included).
  Clock::duration P99(int frames) {
    std::vector<Clock::duration> times;
    for (int i = 0; i < frames; ++i) {
      v1::SessionRequest request;
      SetDescriptor(*request.mutable_frame(), SyntheticDescriptor(i));
      request.mutable_frame()->set_azimuth_deg((i * 5) % 360);
      const auto start = Clock::now();
      v1::SessionUpdate update;
      if (!stream_->Write(request) || !stream_->Read(&update)) {
        ADD_FAILURE() << "the well-behaved session ended: " << stream_->Finish().error_message();
        return Clock::duration::max();
      }
      times.push_back(Clock::now() - start);
      std::this_thread::sleep_for(std::chrono::milliseconds(20));  // under --max-fps 60
    }
    std::sort(times.begin(), times.end());
    return times[(times.size() * 99) / 100];
  }

  grpc::Status Close() {
    stream_->WritesDone();
    return stream_->Finish();
  }

 private:
  std::unique_ptr<v1::Recognition::Stub> stub_;
  grpc::ClientContext context_;
  std::unique_ptr<grpc::ClientReaderWriter<v1::SessionRequest, v1::SessionUpdate>> stream_;
};

// The bound a well-behaved session's p99 keeps under attack: a few times its own p99 measured
// just before on the same server, plus a margin for a machine shared with the attacker.
inline std::chrono::steady_clock::duration KeptP99(std::chrono::steady_clock::duration baseline) {
  return 3 * baseline + std::chrono::milliseconds(50);
}

inline double Milliseconds(std::chrono::steady_clock::duration d) {
  return std::chrono::duration<double, std::milli>(d).count();
}

}  // namespace orbit::testing
