// CEDD extraction speed against a memory-bound baseline measured in the same run: a
// single-threaded BGR->grey conversion of the same frame (one read of every pixel).
//
// Frames are a real photograph from the conformance set, resized (INTER_AREA) to each size.
// The product's budgets: product-describe/640x480, the device side of the product
// pipeline on one frame (core/engines/product_pipeline.h, its variant), at most 6x
// bgr2gray/640x480; product-enroll-view/128x128, what enrolling one view costs (descriptor, its
// distorted copies and typical distance: DescribeView), under 10 ms, and view-distortion/*, the
// two copies alone. Run: build/orbit_bench
// --benchmark_filter='cedd|bgr2gray|noise-estimate|product-|view-distortion'

#include <benchmark/benchmark.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "bench/bench_data.h"
#include "client/image_file.h"
#include "core/descriptor/cedd.h"
#include "core/descriptor/distortion.h"
#include "core/descriptor/noise_estimate.h"
#include "core/descriptor/view_description.h"
#include "core/engines/product_pipeline.h"

namespace orbit {
namespace {

cv::Mat Frame(int width, int height) {
  static const cv::Mat photo = ReadImageFile(
      (bench::DataDir() / "cedd-conformance/photos/011_2828686873_2fa36f83d7_b.png").string());
  cv::Mat frame;
  cv::resize(photo, frame, cv::Size(width, height), 0, 0, cv::INTER_AREA);
  return frame;
}

void BM_Cedd(benchmark::State& state, DescriptorVariant variant, int width, int height) {
  const cv::Mat frame = Frame(width, height);
  for (auto _ : state) benchmark::DoNotOptimize(ExtractCedd(frame, variant));
  state.SetItemsProcessed(state.iterations());
}

void BM_Bgr2Gray(benchmark::State& state, int width, int height) {
  const cv::Mat frame = Frame(width, height);
  cv::Mat grey;
  for (auto _ : state) {
    cv::cvtColor(frame, grey, cv::COLOR_BGR2GRAY);
    benchmark::DoNotOptimize(grey.data);
  }
}

// The noise estimate a robust pipeline reads on every frame (core/descriptor/noise_estimate.h).
void BM_NoiseEstimate(benchmark::State& state, int width, int height) {
  const cv::Mat frame = Frame(width, height);
  for (auto _ : state) benchmark::DoNotOptimize(EstimateNoiseSigma(frame));
}

// The two distorted copies a view's typical distance describes (core/descriptor/distortion.h).
void BM_MotionBlur(benchmark::State& state, int width, int height) {
  const cv::Mat frame = Frame(width, height);
  for (auto _ : state) benchmark::DoNotOptimize(MotionBlur(frame));
}

void BM_GaussianNoise(benchmark::State& state, int width, int height) {
  const cv::Mat frame = Frame(width, height);
  std::uint64_t seed = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(AddGaussianNoise(frame, kGaussianNoiseVariance, ++seed));
  }
}

// What a view costs to enroll in the product's variant.
void BM_EnrollView(benchmark::State& state, int width, int height) {
  const cv::Mat frame = Frame(width, height);
  for (auto _ : state) benchmark::DoNotOptimize(DescribeView(frame, Product().variant));
}

int RegisterCeddBenchmarks() {
  struct Size {
    int width, height;
  };
  for (const Size s : {Size{128, 128}, Size{640, 480}, Size{1280, 720}}) {
    for (const DescriptorVariant v : kDescriptorVariants) {
      const std::string name = std::string(VariantName(v)) + "/" + std::to_string(s.width) + "x" +
                               std::to_string(s.height);
      benchmark::RegisterBenchmark(name.c_str(), BM_Cedd, v, s.width, s.height);
    }
  }
  benchmark::RegisterBenchmark("bgr2gray/640x480", BM_Bgr2Gray, 640, 480);
  benchmark::RegisterBenchmark("product-describe/640x480", BM_Cedd, Product().variant, 640, 480);
  benchmark::RegisterBenchmark("product-enroll-view/128x128", BM_EnrollView, 128, 128)
      ->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark("view-distortion/motion-blur/128x128", BM_MotionBlur, 128, 128)
      ->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark("view-distortion/gaussian-noise/128x128", BM_GaussianNoise, 128, 128)
      ->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark("noise-estimate/128x128", BM_NoiseEstimate, 128, 128);
  benchmark::RegisterBenchmark("noise-estimate/640x480", BM_NoiseEstimate, 640, 480);
  return 0;
}

const int registered = RegisterCeddBenchmarks();

}  // namespace
}  // namespace orbit
