// What a generated catalogue object costs before it reaches the store: its 72 views rendered and
// described as `orbit import --layout distractors` does (evaluation/distractor_objects.h), each
// view with its two distorted copies and typical distance, on one thread. Ten thousand objects
// on two CPUs take 10,000 x distractor-object/72 / 2 at the least, whatever the store and the
// enrollment report add. The parts: distractor-render/128x128 paints one view from its cast rays;
// the distortions and the description of one view are in cedd_bench.cc
// (view-distortion/*, cedd-hsv-hog/128x128, product-enroll-view/128x128).
// Run: build/orbit_bench
// --benchmark_filter='distractor|view-distortion|product-enroll|cedd-hsv-hog/128'

#include <benchmark/benchmark.h>

#include "core/engines/product_pipeline.h"
#include "evaluation/distractor_objects.h"
#include "evaluation/synthetic_object.h"

namespace orbit {
namespace {

const DistractorObjects& Distractors() {
  static const DistractorObjects distractors(1, 0);
  return distractors;
}

void BM_DistractorObject(benchmark::State& state) {
  const DistractorObjects& distractors = Distractors();
  int k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(distractors.Views(k % 100 + 1, Product().variant, 1));
    ++k;
  }
}

void BM_DistractorRender(benchmark::State& state) {
  const SyntheticObject object = RandomSyntheticObject(7, "distractor");
  const ViewRays rays = CastViewRays(object.shape, 35);
  for (auto _ : state) benchmark::DoNotOptimize(RenderView(object, rays));
}

int RegisterDistractorBenchmarks() {
  benchmark::RegisterBenchmark("distractor-object/72", BM_DistractorObject)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("distractor-render/128x128", BM_DistractorRender)
      ->Unit(benchmark::kMicrosecond);
  return 0;
}

const int registered = RegisterDistractorBenchmarks();

}  // namespace
}  // namespace orbit
