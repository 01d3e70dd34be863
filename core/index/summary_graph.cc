#include "core/index/summary_graph.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <mutex>

#include <hnswlib/hnswlib.h>

#include "core/base/cpu_dispatch.h"

namespace orbit {
namespace {

// The largest byte magnitude of a kCosineBytes value.
constexpr float kByteScale = 127;

// sum of a[i] * b[i], exact in 32 bits for up to 2^17 values, on either hot-loop path.
ORBIT_HOT_LOOP std::int32_t ByteDot(const std::int8_t* __restrict a,
                                    const std::int8_t* __restrict b, std::size_t n) {
  std::int32_t sum = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sum += static_cast<std::int16_t>(a[i]) * static_cast<std::int16_t>(b[i]);
  }
  return sum;
}

// kCosineBytes' distance between two stored vectors: [float scale][int8 value] * dimensions,
// `param` pointing to the dimensions. The scales are the unit vectors' largest magnitude / 127,
// so scale_a * scale_b * (a . b) is the cosine up to the rounding.
float ByteCosineDistance(const void* a, const void* b, const void* param) {
  const std::size_t dimensions = *static_cast<const std::size_t*>(param);
  float scale_a = 0, scale_b = 0;
  std::memcpy(&scale_a, a, sizeof(float));
  std::memcpy(&scale_b, b, sizeof(float));
  const std::int32_t dot = RunHotLoop<ByteDot>(
      reinterpret_cast<const std::int8_t*>(static_cast<const char*>(a) + sizeof(float)),
      reinterpret_cast<const std::int8_t*>(static_cast<const char*>(b) + sizeof(float)),
      dimensions);
  return 1.0f - scale_a * scale_b * static_cast<float>(dot);
}

// hnswlib's space for kCosineBytes: each vector is a float and `dimensions` bytes.
class ByteCosineSpace final : public hnswlib::SpaceInterface<float> {
 public:
  explicit ByteCosineSpace(std::size_t dimensions) : dimensions_(dimensions) {}
  std::size_t get_data_size() override { return sizeof(float) + dimensions_; }
  hnswlib::DISTFUNC<float> get_dist_func() override { return ByteCosineDistance; }
  void* get_dist_func_param() override { return &dimensions_; }

 private:
  std::size_t dimensions_;
};

}  // namespace

struct SummaryGraph::Graph {
  std::unique_ptr<hnswlib::SpaceInterface<float>> space;
  std::unique_ptr<hnswlib::HierarchicalNSW<float>> hnsw;
};

SummaryGraph::SummaryGraph(std::size_t dimensions, std::size_t capacity, Options options)
    : graph_(std::make_unique<Graph>()), dimensions_(dimensions), metric_(options.metric) {
  switch (metric_) {
    case Metric::kCosine:
      graph_->space = std::make_unique<hnswlib::InnerProductSpace>(dimensions);
      break;
    case Metric::kCosineBytes: graph_->space = std::make_unique<ByteCosineSpace>(dimensions); break;
    case Metric::kEuclidean: graph_->space = std::make_unique<hnswlib::L2Space>(dimensions); break;
  }
  graph_->hnsw = std::make_unique<hnswlib::HierarchicalNSW<float>>(
      graph_->space.get(), capacity, options.links, options.build_breadth, options.seed);
}

SummaryGraph::~SummaryGraph() = default;

void SummaryGraph::Store(const float* point, std::vector<char>& stored) const {
  if (metric_ == Metric::kEuclidean) {
    stored.resize(dimensions_ * sizeof(float));
    std::memcpy(stored.data(), point, stored.size());
    return;
  }
  float squared = 0, largest = 0;
  for (std::size_t i = 0; i < dimensions_; ++i) {
    squared += point[i] * point[i];
    largest = std::max(largest, std::abs(point[i]));
  }
  const float norm = std::sqrt(squared);
  if (metric_ == Metric::kCosine) {
    stored.resize(dimensions_ * sizeof(float));
    auto* unit = reinterpret_cast<float*>(stored.data());
    for (std::size_t i = 0; i < dimensions_; ++i) unit[i] = norm > 0 ? point[i] / norm : 0.0f;
    return;
  }
  // kCosineBytes: zeros stay zeros (scale 0: every distance from them is 1).
  stored.assign(sizeof(float) + dimensions_, 0);
  if (largest == 0) return;
  const float scale = largest / norm / kByteScale;
  std::memcpy(stored.data(), &scale, sizeof(float));
  for (std::size_t i = 0; i < dimensions_; ++i) {
    stored[sizeof(float) + i] =
        static_cast<char>(static_cast<std::int8_t>(std::lround(point[i] / largest * kByteScale)));
  }
}

void SummaryGraph::Add(const float* point, std::size_t label) {
  std::vector<char> stored;
  Store(point, stored);
  graph_->hnsw->addPoint(stored.data(), label);
}

void SummaryGraph::SetBreadth(std::size_t breadth) { graph_->hnsw->setEf(breadth); }

void SummaryGraph::Search(const float* query, std::size_t count,
                          std::vector<std::size_t>& labels) const {
  labels.clear();
  if (count == 0 || graph_->hnsw->cur_element_count == 0) return;
  thread_local std::vector<char> stored;
  Store(query, stored);
  for (auto found = graph_->hnsw->searchKnn(stored.data(), count); !found.empty(); found.pop()) {
    labels.push_back(found.top().second);
  }
}

double SummaryGraph::Distance(const float* a, const float* b) const {
  std::vector<char> stored_a, stored_b;
  Store(a, stored_a);
  Store(b, stored_b);
  return graph_->space->get_dist_func()(stored_a.data(), stored_b.data(),
                                        graph_->space->get_dist_func_param());
}

double SummaryGraph::Bytes() const {
  const hnswlib::HierarchicalNSW<float>& h = *graph_->hnsw;
  double bytes = static_cast<double>(h.max_elements_) * h.size_data_per_element_;
  for (std::size_t i = 0; i < h.cur_element_count; ++i) {
    bytes += static_cast<double>(h.element_levels_[i]) * h.size_links_per_element_;
  }
  // Per element: its lock, level, upper-link pointer and visited mark, and its label's hash
  // table node (about 4 words).
  bytes +=
      static_cast<double>(h.max_elements_) * (sizeof(std::mutex) + sizeof(int) + sizeof(char*) +
                                              sizeof(unsigned short) + 4 * sizeof(void*));
  return bytes;
}

}  // namespace orbit
