#include "core/index/summary_graph.h"

#include <cmath>
#include <mutex>

#include <hnswlib/hnswlib.h>

namespace orbit {
namespace {

// `point` scaled to length 1 into `unit` (zeros stay zeros).
void ScaleToUnit(const float* point, std::size_t dimensions, std::vector<float>& unit) {
  float squared = 0;
  for (std::size_t i = 0; i < dimensions; ++i) squared += point[i] * point[i];
  const float norm = std::sqrt(squared);
  unit.resize(dimensions);
  for (std::size_t i = 0; i < dimensions; ++i) unit[i] = norm > 0 ? point[i] / norm : 0.0f;
}

}  // namespace

struct SummaryGraph::Graph {
  std::unique_ptr<hnswlib::SpaceInterface<float>> space;
  std::unique_ptr<hnswlib::HierarchicalNSW<float>> hnsw;
};

SummaryGraph::SummaryGraph(std::size_t dimensions, std::size_t capacity, Options options)
    : graph_(std::make_unique<Graph>()), dimensions_(dimensions), metric_(options.metric) {
  if (metric_ == Metric::kCosine) {
    graph_->space = std::make_unique<hnswlib::InnerProductSpace>(dimensions);
  } else {
    graph_->space = std::make_unique<hnswlib::L2Space>(dimensions);
  }
  graph_->hnsw = std::make_unique<hnswlib::HierarchicalNSW<float>>(
      graph_->space.get(), capacity, options.links, options.build_breadth, options.seed);
}

SummaryGraph::~SummaryGraph() = default;

void SummaryGraph::Add(const float* point, std::size_t label) {
  if (metric_ == Metric::kEuclidean) {
    graph_->hnsw->addPoint(point, label);
    return;
  }
  std::vector<float> unit;
  ScaleToUnit(point, dimensions_, unit);
  graph_->hnsw->addPoint(unit.data(), label);
}

void SummaryGraph::SetBreadth(std::size_t breadth) { graph_->hnsw->setEf(breadth); }

void SummaryGraph::Search(const float* query, std::size_t count,
                          std::vector<std::size_t>& labels) const {
  labels.clear();
  if (count == 0 || graph_->hnsw->cur_element_count == 0) return;
  thread_local std::vector<float> unit;
  if (metric_ == Metric::kCosine) {
    ScaleToUnit(query, dimensions_, unit);
    query = unit.data();
  }
  for (auto found = graph_->hnsw->searchKnn(query, count); !found.empty(); found.pop()) {
    labels.push_back(found.top().second);
  }
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
