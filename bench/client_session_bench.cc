// Speed of the client library end to end: what one frame costs a device from Push()
// to its update, against an in-process OrbitServer on loopback holding COIL-100 objects 1-20
// enrolled every 10 degrees (720 views, kd-tree index, default VCI session, W = 8), and what one
// view costs a device at enrollment.
//
//   client/enroll-view              ComputeView: CEDD + two distorted copies + their CEDDs
//   client/session-frame/image      Push(128x128 image) + NextUpdate(): CEDD on the device,
//                                   gRPC round trip, server engine work
//   client/session-frame/descriptor PushDescriptor + NextUpdate(): round trip and server only
//
// Frames cycle through object 7's views at 5, 15, ..., 355 degrees (never enrolled views), so the
// window is always full after the first 8. The server shares the machine with the client.
//
// Run: build/orbit_bench --benchmark_filter='client/'
#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <unistd.h>

#include "bench/bench_data.h"
#include "client/connection.h"
#include "client/enroller.h"
#include "client/image_file.h"
#include "client/recognition_session.h"
#include "core/descriptor/cedd.h"
#include "server/orbit_server.h"

namespace orbit {
namespace {

std::filesystem::path CoilDir() { return bench::DataDir() / "coil-100"; }

cv::Mat Coil(int object, int azimuth) {
  return ReadImageFile(
      (CoilDir() / ("obj" + std::to_string(object) + "__" + std::to_string(azimuth) + ".png"))
          .string());
}

// One server for every benchmark here, enrolled once.
struct LoopbackServer {
  std::filesystem::path folder;
  std::unique_ptr<server::OrbitServer> server;
  std::unique_ptr<Connection> connection;

  LoopbackServer() {
    folder = std::filesystem::temp_directory_path() /
             ("orbit_client_bench_" + std::to_string(::getpid()));
    std::filesystem::create_directories(folder);
    server::ServerConfig config;
    config.database = folder / "models.db";
    config.listen = "127.0.0.1:0";
    config.limits.max_frames_per_second = 1e6;  // measure the work, not the rate limit
    server = std::make_unique<server::OrbitServer>(config);
    ConnectionOptions options;
    options.address = server->address();
    connection = std::make_unique<Connection>(options);
    Enroller enroller(*connection, {.seed = 1, .threads = 2});
    for (int object = 1; object <= 20; ++object) {
      std::vector<EnrollmentImage> images;
      for (int a = 0; a < 360; a += 10) images.push_back({Coil(object, a), double(a), {}, {}});
      enroller.Enroll("obj" + std::to_string(object), images);
    }
  }
  ~LoopbackServer() {
    connection.reset();
    server->Shutdown();
    server.reset();
    std::filesystem::remove_all(folder);
  }
};

LoopbackServer& Server() {
  static LoopbackServer instance;
  return instance;
}

std::vector<cv::Mat> QueryImages() {
  std::vector<cv::Mat> images;
  for (int a = 5; a < 360; a += 10) images.push_back(Coil(7, a));
  return images;
}

void EnrollView(benchmark::State& state) {
  const EnrollmentImage image{Coil(7, 40), 40, {}, {}};
  std::uint64_t seed = 1;
  for (auto _ : state) {
    benchmark::DoNotOptimize(ComputeView(image, DescriptorVariant::kCeddLire, seed++));
  }
}

void SessionFrame(benchmark::State& state, bool send_image) {
  const std::vector<cv::Mat> images = QueryImages();
  std::vector<DescriptorValues> descriptors;
  for (const cv::Mat& image : images) {
    descriptors.push_back(ExtractCedd(image, DescriptorVariant::kCeddLire).values);
  }
  auto session = RecognitionSession::Open(*Server().connection, {});
  std::size_t k = 0;
  for (auto _ : state) {
    const std::size_t i = k % images.size();
    const double azimuth = 5.0 + 10.0 * static_cast<double>(k);
    if (send_image) {
      session->Push(images[i], azimuth);
    } else {
      session->PushDescriptor(descriptors[i], azimuth);
    }
    if (!session->NextUpdate()) {
      state.SkipWithError("the session ended");
      break;
    }
    ++k;
  }
  session->Close();
}

void SessionFrameImage(benchmark::State& state) { SessionFrame(state, true); }
void SessionFrameDescriptor(benchmark::State& state) { SessionFrame(state, false); }

const bool registered = [] {
  benchmark::RegisterBenchmark("client/enroll-view", EnrollView)->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark("client/session-frame/image", SessionFrameImage)
      ->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark("client/session-frame/descriptor", SessionFrameDescriptor)
      ->Unit(benchmark::kMicrosecond);
  return true;
}();

}  // namespace
}  // namespace orbit
