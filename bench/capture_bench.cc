// The device's per-frame cost of a capture, against bgr2gray/640x480 of the same run
// (bench/cedd_bench.cc): following the object with each tracker (client/object_tracker.h) and
// measuring the frame's quality (client/frame_quality.h). Frames are a generated walk
// (evaluation/capture_generator.h) at 640x480, the object about 220 pixels across; the tracker
// is started on the first frame and fed the next ones in turn, restarted after the last.
// device-frame/640x480 is everything a device computes for one frame before it sends it
// (client/recognition_session.h, Push): the default tracker's box, the frame's quality in that
// box and the product's descriptor of that box; device-frame/serialise is the frame message
// built from the descriptor and serialised, as Push hands it to gRPC.
// Run: build/orbit_bench --benchmark_filter='track-|frame-quality|device-frame|bgr2gray'
// (track-default/640x480 is the default tracker, also listed under its own name).

#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "api/conversion.h"
#include "bench/bench_data.h"
#include "client/frame_quality.h"
#include "client/object_tracker.h"
#include "core/descriptor/cedd.h"
#include "core/engines/product_pipeline.h"
#include "evaluation/capture_generator.h"
#include "orbit/v1/recognition.pb.h"

namespace orbit {
namespace {

GeneratedCapture MakeWalk(cv::Size size) {
  CaptureGeneratorOptions options;
  options.coil_dir = bench::DataDir() / "coil-100";
  options.object = 5;
  options.frame_size = size;
  options.frames = 72;
  return GenerateCapture(options);
}

const GeneratedCapture& Walk() {
  static const GeneratedCapture walk = MakeWalk(cv::Size(640, 480));
  return walk;
}

const GeneratedCapture& SmallWalk() {
  static const GeneratedCapture walk = MakeWalk(cv::Size(320, 240));
  return walk;
}

void BM_Track(benchmark::State& state, TrackerKind kind, bool small) {
  const GeneratedCapture& walk = small ? SmallWalk() : Walk();
  std::unique_ptr<ObjectTracker> tracker;
  std::size_t next = walk.frames.size();
  for (auto _ : state) {
    if (next == walk.frames.size()) {
      state.PauseTiming();
      tracker = std::make_unique<ObjectTracker>(walk.frames[0], walk.true_boxes[0], kind);
      next = 1;
      state.ResumeTiming();
    }
    benchmark::DoNotOptimize(tracker->Track(walk.frames[next++]));
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_FrameQuality(benchmark::State& state, bool region) {
  const GeneratedCapture& walk = Walk();
  std::size_t f = 0;
  for (auto _ : state) {
    const std::optional<cv::Rect> box =
        region ? std::optional<cv::Rect>(walk.true_boxes[f]) : std::nullopt;
    benchmark::DoNotOptimize(MeasureFrameQuality(walk.frames[f], box));
    f = (f + 1) % walk.frames.size();
  }
}

// Track, measure the quality in the tracked box, describe the box: one frame of a capture.
void BM_DeviceFrame(benchmark::State& state) {
  const GeneratedCapture& walk = Walk();
  const DescriptorVariant variant = Product().variant;
  std::unique_ptr<ObjectTracker> tracker;
  std::size_t next = walk.frames.size();
  double lost = 0;
  for (auto _ : state) {
    if (next == walk.frames.size()) {
      state.PauseTiming();
      tracker = std::make_unique<ObjectTracker>(walk.frames[0], walk.true_boxes[0]);
      next = 1;
      state.ResumeTiming();
    }
    const cv::Mat& frame = walk.frames[next++];
    const TrackedBox tracked = tracker->Track(frame);
    if (tracked.lost) {  // not described nor sent (client/capture_session.h)
      ++lost;
      continue;
    }
    benchmark::DoNotOptimize(MeasureFrameQuality(frame, tracked.box));
    benchmark::DoNotOptimize(ExtractCedd(frame, variant, tracked.box));
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["lost"] = benchmark::Counter(lost, benchmark::Counter::kAvgIterations);
}

// The frame message of one described frame, serialised: what Push adds before gRPC's own work.
void BM_SerialiseFrame(benchmark::State& state) {
  const GeneratedCapture& walk = Walk();
  const DescriptorVariant variant = Product().variant;
  const DescriptorValues descriptor =
      ExtractCedd(walk.frames[0], variant, walk.true_boxes[0]).values;
  const FrameQuality quality = MeasureFrameQuality(walk.frames[0], walk.true_boxes[0]);
  std::string bytes;
  for (auto _ : state) {
    v1::SessionRequest request;
    v1::Frame* frame = request.mutable_frame();
    SetWireDescriptor(descriptor, variant, frame->mutable_cedd(), frame->mutable_appearance());
    frame->set_azimuth_deg(35);
    *frame->mutable_quality() = ToProtoFrameQuality(quality);
    request.SerializeToString(&bytes);
    benchmark::DoNotOptimize(bytes.data());
  }
  state.counters["bytes"] = static_cast<double>(bytes.size());
}

int RegisterCaptureBenchmarks() {
  // Whichever tracker a capture gets when it names none: what a device pays by default.
  benchmark::RegisterBenchmark("track-default/640x480", BM_Track, kDefaultTracker, false)
      ->Unit(benchmark::kMicrosecond);
  for (TrackerKind kind : kTrackerKinds) {
    const std::string name = "track-" + std::string(TrackerName(kind)) + "/640x480";
    benchmark::RegisterBenchmark(name.c_str(), BM_Track, kind, false)
        ->Unit(benchmark::kMicrosecond);
    const std::string small = "track-" + std::string(TrackerName(kind)) + "/320x240";
    benchmark::RegisterBenchmark(small.c_str(), BM_Track, kind, true)
        ->Unit(benchmark::kMicrosecond);
  }
  benchmark::RegisterBenchmark("frame-quality/640x480", BM_FrameQuality, false)
      ->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark("frame-quality/object-region", BM_FrameQuality, true)
      ->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark("device-frame/640x480", BM_DeviceFrame)
      ->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark("device-frame/serialise", BM_SerialiseFrame)
      ->Unit(benchmark::kMicrosecond);
  return 0;
}

const int registered = RegisterCaptureBenchmarks();

}  // namespace
}  // namespace orbit
