// What the server's metrics cost (server/server_metrics.h, on prometheus-cpp): the updates every
// answered frame makes, which must stay far below the frame's own cost (a descriptor frame is
// meant to take under 25 us of server CPU), and what a Prometheus scrape costs.
//
//   metrics/frame                one frame's updates, as SessionReactor::Process makes them:
//                                FrameMetrics::Record (the engine's frame counter, the frame
//                                latency histogram), latencies cycling over 12..140 us
//   metrics/frame/threads:2      the same from two threads at once on the same counters (the
//                                cache lines move between cores: the contended cost)
//   metrics/histogram-observe    one Histogram::Observe on the frame latency buckets
//   metrics/counter-increment    one Counter::Increment
//   metrics/expose               the whole exposition of a fresh ServerMetrics, as a scrape
//                                renders it (without the gauges, which read the server)
//
// Run: build/orbit_bench --benchmark_filter='metrics/'
#include <benchmark/benchmark.h>
#include <prometheus/counter.h>
#include <prometheus/histogram.h>

#include <array>
#include <chrono>

#include "server/server_metrics.h"

namespace orbit {
namespace {

using server::FrameInput;

// Frame latencies around the target, so that the bucket scan does its usual amount of work.
constexpr std::array<std::chrono::nanoseconds, 8> kSpent = {
    std::chrono::microseconds(12), std::chrono::microseconds(18), std::chrono::microseconds(21),
    std::chrono::microseconds(24), std::chrono::microseconds(30), std::chrono::microseconds(45),
    std::chrono::microseconds(80), std::chrono::microseconds(140)};

server::ServerMetrics& SharedMetrics() {
  static server::ServerMetrics metrics;
  return metrics;
}

void BM_FrameMetrics(benchmark::State& state) {
  const server::FrameMetrics frame = SharedMetrics().ForEngine(v1::ENGINE_HMM);
  std::size_t i = 0;
  for (auto _ : state) {
    frame.Record(FrameInput::kCedd, kSpent[i++ % kSpent.size()]);
  }
}
BENCHMARK(BM_FrameMetrics)->Name("metrics/frame");
BENCHMARK(BM_FrameMetrics)->Name("metrics/frame")->Threads(2)->UseRealTime();

void BM_HistogramObserve(benchmark::State& state) {
  prometheus::Histogram histogram({1e-5, 2.5e-5, 5e-5, 1e-4, 2.5e-4, 5e-4, 1e-3, 2.5e-3, 5e-3, 0.01,
                                   0.025, 0.05, 0.1, 0.25, 0.5, 1});
  std::size_t i = 0;
  for (auto _ : state) {
    histogram.Observe(std::chrono::duration<double>(kSpent[i++ % kSpent.size()]).count());
  }
}
BENCHMARK(BM_HistogramObserve)->Name("metrics/histogram-observe");

void BM_CounterIncrement(benchmark::State& state) {
  prometheus::Counter counter;
  for (auto _ : state) counter.Increment();
  benchmark::DoNotOptimize(counter.Value());
}
BENCHMARK(BM_CounterIncrement)->Name("metrics/counter-increment");

void BM_Expose(benchmark::State& state) {
  const server::ServerMetrics metrics;
  std::size_t bytes = 0;
  for (auto _ : state) {
    const std::string text = metrics.Expose();
    bytes = text.size();
    benchmark::DoNotOptimize(text.data());
  }
  state.counters["bytes"] = static_cast<double>(bytes);
}
BENCHMARK(BM_Expose)->Name("metrics/expose")->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace orbit
