// build/orbit_grpc_floor: what gRPC and the kernel alone let a server reach on this machine, for
// the closed-loop goals of docs/results/load.md ("The floor under the server").
//
//   orbit_grpc_floor [--listen ADDR] [--work-us US] [--touch-kb KB] [--session-kb KB]
//
// A stand-in for `orbit serve` that `orbit loadtest` can drive: it answers Models.ServerInfo
// (variant cedd-lire, no frame-rate limit) and Recognition.Session, where each frame gets an
// update echoing its timestamp after WORK_US microseconds of busy work, on gRPC's callback API
// exactly as the real server runs it (the frame is handled in the read's reaction). The work
// reads a buffer of TOUCH_KB kilobytes a cache line at a time (0: it only spins), so that a run
// can stand for an engine of a given cost with or without a working set that evicts gRPC's.
// With SESSION_KB, each session also owns that many kilobytes, which every one of its frames
// reads a cache line at a time in a scattered order (as an engine reads its session's window)
// before the busy work: where 8 sessions' memory stays in cache and 256 sessions' does not,
// this is what reading it costs per frame, and so what any engine whose frames read that much
// memory of their own loses from 8 to 256 sessions on this machine.
// Nothing else: no model set, no validation, no rate limits. What it reaches at the engine's
// cost is the most any server on this API and transport could reach on the same machine.
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <grpcpp/grpcpp.h>

#include "orbit/v1/models.grpc.pb.h"
#include "orbit/v1/recognition.grpc.pb.h"

namespace {

namespace v1 = orbit::v1;
using Clock = std::chrono::steady_clock;

struct FloorOptions {
  std::string listen = "127.0.0.1:50551";
  int work_us = 0;
  int touch_kb = 0;
  int session_kb = 0;
};

// The stand-in engine: busy for `work_us`, reading `buffer` a cache line at a time from where
// the previous frame stopped (so a buffer larger than the caches keeps missing them).
class BusyWork {
 public:
  BusyWork(int work_us, int touch_kb)
      : work_(std::chrono::microseconds(work_us)),
        buffer_(static_cast<std::size_t>(touch_kb) * 1024, 1) {}

  std::uint64_t Run() {
    const Clock::time_point end = Clock::now() + work_;
    std::uint64_t sum = 0;
    std::size_t at = position_.load(std::memory_order_relaxed);
    do {
      for (int line = 0; line < 64 && !buffer_.empty(); ++line) {
        sum += buffer_[at];
        at += 64;
        if (at >= buffer_.size()) at = 0;
      }
    } while (Clock::now() < end);
    position_.store(at, std::memory_order_relaxed);
    return sum;
  }

 private:
  const Clock::duration work_;
  const std::vector<std::uint8_t> buffer_;
  std::atomic<std::size_t> position_{0};
};

class FloorSession final : public grpc::ServerBidiReactor<v1::SessionRequest, v1::SessionUpdate> {
 public:
  FloorSession(BusyWork& work, int session_kb)
      : work_(work), own_(static_cast<std::size_t>(session_kb) * 1024, 1) {
    StartRead(&request_);
  }

  void OnReadDone(bool ok) override {
    if (!ok) {
      Finish(grpc::Status::OK);
      return;
    }
    if (!request_.has_frame()) {  // the opening request: nothing to answer
      StartRead(&request_);
      return;
    }
    const Clock::time_point start = Clock::now();
    sink_ += ReadOwn();
    sink_ += work_.Run();
    update_.Clear();
    update_.set_frame_index(frames_++);
    update_.set_timestamp_us(request_.frame().timestamp_us());
    update_.set_processing_time_us(
        std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - start).count());
    StartWrite(&update_);
  }

  void OnWriteDone(bool ok) override {
    if (!ok) {
      Finish(grpc::Status::OK);
      return;
    }
    StartRead(&request_);
  }

  void OnDone() override { delete this; }

 private:
  // Every line of the session's memory once, 97 lines apart (mod its line count), so that the
  // hardware's stream prefetcher does not hide the misses but the reads stay independent.
  std::uint64_t ReadOwn() const {
    const std::size_t lines = own_.size() / 64;
    const std::size_t stride = lines % 97 == 0 ? 1 : 97;  // visits every line once
    std::uint64_t sum = 0;
    for (std::size_t i = 0, line = 0; i < lines; ++i, line = (line + stride) % lines) {
      sum += own_[line * 64];
    }
    return sum;
  }

  BusyWork& work_;
  const std::vector<std::uint8_t> own_;
  v1::SessionRequest request_;
  v1::SessionUpdate update_;
  std::int64_t frames_ = 0;
  std::uint64_t sink_ = 0;
};

class FloorRecognition final : public v1::Recognition::CallbackService {
 public:
  FloorRecognition(BusyWork& work, int session_kb) : work_(work), session_kb_(session_kb) {}
  grpc::ServerBidiReactor<v1::SessionRequest, v1::SessionUpdate>* Session(
      grpc::CallbackServerContext*) override {
    return new FloorSession(work_, session_kb_);
  }

 private:
  BusyWork& work_;
  const int session_kb_;
};

class FloorModels final : public v1::Models::CallbackService {
 public:
  grpc::ServerUnaryReactor* ServerInfo(grpc::CallbackServerContext* context,
                                       const v1::ServerInfoRequest*,
                                       v1::ServerInfoResponse* response) override {
    response->set_version("grpc-floor");
    response->set_variant(v1::CEDD_LIRE);
    response->mutable_session_defaults()->set_engine(v1::ENGINE_HMM);
    response->mutable_limits()->set_max_frames_per_second(1e9);
    response->mutable_limits()->set_max_sessions(100000);
    grpc::ServerUnaryReactor* reactor = context->DefaultReactor();
    reactor->Finish(grpc::Status::OK);
    return reactor;
  }
};

constexpr const char* kUsage =
    "usage: orbit_grpc_floor [--listen ADDR (127.0.0.1:50551)] [--work-us US (>= 0, 0)] "
    "[--touch-kb KB (>= 0, 0)] [--session-kb KB (>= 0, 0)]\n";

int Usage(const std::string& why) {
  std::cerr << "orbit_grpc_floor: " << why << "\n" << kUsage;
  return 2;
}

std::atomic<bool> stop{false};

}  // namespace

int main(int argc, char** argv) {
  FloorOptions options;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "--help" || flag == "-h") {
      std::cout << "orbit_grpc_floor: a stand-in server for `orbit loadtest` that answers each "
                   "frame after\nbusy work only, to measure what gRPC and the kernel cost "
                   "(docs/results/load.md,\n\"The floor under the server\").\n"
                << kUsage;
      return 0;
    }
    if (i + 1 >= argc) return Usage("missing value of " + flag);
    const std::string value = argv[++i];
    if (flag == "--listen") {
      options.listen = value;
    } else if (flag == "--work-us" || flag == "--touch-kb" || flag == "--session-kb") {
      const int v = std::atoi(value.c_str());
      if (v < 0 || (v == 0 && value != "0")) return Usage(flag + " must be an integer >= 0");
      (flag == "--work-us"    ? options.work_us
       : flag == "--touch-kb" ? options.touch_kb
                              : options.session_kb) = v;
    } else {
      return Usage("unknown flag " + flag);
    }
  }

  BusyWork work(options.work_us, options.touch_kb);
  FloorRecognition recognition(work, options.session_kb);
  FloorModels models;
  grpc::ServerBuilder builder;
  int port = 0;
  builder.AddListeningPort(options.listen, grpc::InsecureServerCredentials(), &port);
  builder.RegisterService(&recognition);
  builder.RegisterService(&models);
  std::unique_ptr<grpc::Server> server = builder.BuildAndStart();
  if (!server || port == 0) {
    std::cerr << "orbit_grpc_floor: cannot listen on " << options.listen << "\n";
    return 1;
  }
  std::cerr << "orbit_grpc_floor: listening on " << options.listen << ", " << options.work_us
            << " us of work per frame over " << options.touch_kb << " KB, " << options.session_kb
            << " KB of its own per session\n";
  std::signal(SIGINT, [](int) { stop = true; });
  std::signal(SIGTERM, [](int) { stop = true; });
  while (!stop) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  server->Shutdown(std::chrono::system_clock::now() + std::chrono::seconds(1));
  return 0;
}
