// SummaryGraph: a hierarchical navigable small-world graph (hnswlib's HNSW) over float vectors,
// searched for the nearest ones: what proposes an engine's candidate objects from their sector
// summaries (docs/design.md#object-candidates). The one translation unit of a program that may
// include hnswlib: its headers (Debian's 0.6.2) define global variables.
//
// Thread safety: Search and Bytes may run concurrently with each other; Add on several threads at
// once (hnswlib's locks) once the graph holds a point, but not with a search; SetBreadth only
// while nothing else runs on the graph.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

namespace orbit {

class SummaryGraph {
 public:
  enum class Metric {
    kCosine,  // inner product of the vectors scaled to length 1 (Tanimoto's order, nearly)
    // kCosine on the unit vectors each stored as one scale and a signed byte per value (the
    // value over the vector's largest magnitude, times 127, rounded): a quarter of the memory,
    // and integer products the CPU does 16 at a time (docs/design.md#object-candidates).
    kCosineBytes,
    kEuclidean,  // L2 on the vectors as given
  };
  struct Options {
    Metric metric = Metric::kCosine;
    std::size_t links = 16;           // hnswlib's M: links per node
    std::size_t build_breadth = 100;  // hnswlib's ef_construction
    std::size_t seed = 100;           // the levels' random draws: the same graph for the same adds
  };

  // An empty graph of `dimensions`-value vectors with room for `capacity` of them.
  SummaryGraph(std::size_t dimensions, std::size_t capacity, Options options);
  ~SummaryGraph();
  SummaryGraph(const SummaryGraph&) = delete;
  SummaryGraph& operator=(const SummaryGraph&) = delete;

  // Adds `point` (dimensions values) under `label`. REQUIRES: fewer than capacity points so far.
  void Add(const float* point, std::size_t label);

  // The search breadth (hnswlib's ef): a search looks at max(breadth, count) nodes. Default 0.
  void SetBreadth(std::size_t breadth);

  // Sets `labels` to the labels of the `count` points nearest `query`, nearest last (fewer when
  // the graph holds fewer).
  void Search(const float* query, std::size_t count, std::vector<std::size_t>& labels) const;

  // The memory the graph holds, vectors included.
  double Bytes() const;

  // The distance Search orders by, between two vectors of `dimensions` values as given (the
  // metric's scaling and rounding applied to both): 1 - cosine for the cosine metrics, the
  // squared L2 distance for kEuclidean.
  double Distance(const float* a, const float* b) const;

 private:
  struct Graph;
  // `point` as the graph stores it, in `stored` (the space's data size in bytes).
  void Store(const float* point, std::vector<char>& stored) const;

  std::unique_ptr<Graph> graph_;
  std::size_t dimensions_;
  Metric metric_;
};

}  // namespace orbit
