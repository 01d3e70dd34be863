// Candidate search over sector means: which nearest-neighbour library should propose the objects
// whose HMM states a frame scores exactly, once the catalogue holds 10,000-100,000 objects
// (docs/results/scale.md, "Choosing the candidate index").
//
// Points: the sector means of every object (ComputeSectorViews with 8 sectors: the mean of the
// model views whose azimuth falls in each 45-degree sector, the HMM's state descriptors), as
// floats, 8 per object, point = object * 8 + sector. Sets:
//   <objects>  SyntheticObjects(objects)'s models (bench/synthetic_objects.h), objects = 1000,
//              10000, 100000; queries: 4 frames each of 64 objects spread over the catalogue
//              (SyntheticObjects::Frames, 2.5 degrees off the model views)
//   coil100    COIL-100's cedd-hsv-hog views (480 values) at multiples of 10 degrees; queries:
//              the 3600 views in between
// Truth: exact Tanimoto of the query against every sector mean; an object's score is its best
// sector's, and the truth is the query's top 10 objects by score.
//
//   candidates/exact/<set>           the exact scan: TC against every sector mean, bin-major over
//                                    the query's non-zero values as the HMM's sector table
//                                    scores, then the top 10 objects (the cost to beat)
//   candidates/<library>/<set>/<C>/<knob>:<value>
//                                    one candidate list of C sector means for one query
//
// Libraries (each index is built once, on first use, and its build timed then):
//   flann-kd    FLANN's 4 randomised kd-trees, L2 on the raw means, as the view index uses;
//               knob: checks (leaves visited)
//   flann-kd-cos
//               the same on L2-normalised means and queries, whose L2 order is cosine's
//   hnsw-l2     hnswlib HierarchicalNSW, M = 16, ef_construction = 100, L2 on the raw means;
//               knob: ef (search list size, at least C)
//   hnsw-ip     the same with inner product on L2-normalised means and queries (cosine)
//   hnsw-ip8    the same on the normalised means and queries rounded to a signed byte per value
//               (SummaryGraph's kCosineBytes, what the view index uses)
//   hnsw-ip8-b50
//               the same built with ef_construction = 50 (the build's cost against its recall)
//   faiss-hnsw  faiss IndexHNSWFlat, M = 16, efConstruction = 100, L2; knob: ef (efSearch)
//   faiss-hnsw-ip
//               the same with inner product on L2-normalised means and queries (cosine)
//   faiss-ivf   faiss IndexIVFFlat, L2, round(sqrt(points)) lists trained on 64 points per list;
//               knob: nprobe (lists scanned)
// The -cos and -ip rows tell the metric's share of a library's recall from the library's own.
// hnswlib and faiss build on every core (2 threads here); FLANN builds on one. Every search runs
// on one thread, as a server's frame does.
//
// Counters: recall10, the share of the exact top 10 objects that are among the candidates'
// objects (mean over queries); own, the share of queries whose own object is among them;
// objects, distinct objects per list; build_s, the index's build time; bytes_per_point, the
// memory the index reads per point, vectors included (FLANN does not copy the points but needs
// them, so they count). The time is one search (the candidate list only; the exact scoring of
// its objects is the HMM's, unchanged).
//
// Run: build/orbit_bench --benchmark_filter='^candidates/[^/]+/(1000|10000)(/|$)'
#include <benchmark/benchmark.h>
#include <faiss/IndexFlat.h>
#include <faiss/IndexHNSW.h>
#include <faiss/IndexIVFFlat.h>
#include <omp.h>
#include <flann/flann.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "bench/bench_data.h"
#include "bench/synthetic_objects.h"
#include "client/image_file.h"
#include "core/descriptor/cedd.h"
#include "core/index/indexed_object.h"
#include "core/index/summary_graph.h"

namespace orbit {
namespace {

using bench::SyntheticObjects;

constexpr int kSectors = 8;  // the HMM's states per object
constexpr int kTopObjects = 10;

// Sector means of one catalogue, with its queries and their exact answers.
struct PointSet {
  int dim = 0;  // values per point: the variant's descriptor length
  std::size_t objects = 0;
  std::vector<float> points;                  // [point][dim]
  std::vector<float> by_bin;                  // [bin][point], for the exact scan
  std::vector<float> squared_norms;           // per point
  std::vector<std::vector<float>> queries;    // dim values each
  std::vector<std::size_t> query_object;      // the object each query shows
  std::vector<std::vector<std::size_t>> top;  // per query: its exact top kTopObjects objects

  std::size_t point_count() const { return objects * kSectors; }
  const float* point(std::size_t p) const { return points.data() + p * dim; }
};

void AddSectorMeans(const ObjectModel& model, int dim, std::vector<float>& points) {
  const SectorViews sectors = ComputeSectorViews(model, kSectors);
  for (const MeanDescriptor& mean : sectors.descriptor) {
    points.insert(points.end(), mean.begin(), mean.begin() + dim);
  }
}

// tc[p] = TC(query, point p) for every point: one pass over the points per non-zero value of
// the query (a CEDD has about 21 of 144), then one division per point.
void ExactScan(const PointSet& set, std::span<const float> query, std::vector<float>& tc) {
  const std::size_t n = set.point_count();
  tc.assign(n, 0.0f);
  float qq = 0;
  for (int b = 0; b < set.dim; ++b) {
    const float q = query[b];
    if (q == 0) continue;
    qq += q * q;
    const float* column = set.by_bin.data() + b * n;
    for (std::size_t p = 0; p < n; ++p) tc[p] += q * column[p];
  }
  for (std::size_t p = 0; p < n; ++p) {
    const float qc = tc[p];
    const float denominator = qq + set.squared_norms[p] - qc;
    tc[p] = denominator > 0 ? qc / denominator : 1.0f;  // two zero vectors are alike
  }
}

// The k objects with the highest best-sector TC, best first (ties: lower object first).
std::vector<std::size_t> TopObjects(const std::vector<float>& tc, std::size_t objects, int k,
                                    std::vector<std::pair<float, std::size_t>>& best) {
  best.resize(objects);
  for (std::size_t o = 0; o < objects; ++o) {
    const auto first = tc.begin() + o * kSectors;
    best[o] = {*std::max_element(first, first + kSectors), o};
  }
  const auto better = [](const auto& a, const auto& b) {
    return a.first > b.first || (a.first == b.first && a.second < b.second);
  };
  const std::size_t count = std::min<std::size_t>(k, objects);
  std::partial_sort(best.begin(), best.begin() + count, best.end(), better);
  std::vector<std::size_t> top;
  for (std::size_t i = 0; i < count; ++i) top.push_back(best[i].second);
  return top;
}

// The bin-major copy, the norms and the exact answers, once points and queries are in.
void Finish(PointSet& set) {
  const std::size_t n = set.point_count();
  set.by_bin.resize(n * set.dim);
  set.squared_norms.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    float norm = 0;
    for (int b = 0; b < set.dim; ++b) {
      const float v = set.point(p)[b];
      set.by_bin[b * n + p] = v;
      norm += v * v;
    }
    set.squared_norms[p] = norm;
  }
  std::vector<float> tc;
  std::vector<std::pair<float, std::size_t>> best;
  for (const std::vector<float>& query : set.queries) {
    ExactScan(set, query, tc);
    set.top.push_back(TopObjects(tc, set.objects, kTopObjects, best));
  }
}

// One object's models at a time, so that 100,000 objects never hold their 72 views each at
// once.
std::unique_ptr<PointSet> SyntheticSet(int objects) {
  auto set = std::make_unique<PointSet>();
  set->dim = kCeddSize;
  set->objects = objects;
  SyntheticObjects source(objects);
  set->points.reserve(set->point_count() * set->dim);
  for (int o = 0; o < objects; ++o) AddSectorMeans(source.Model(o), set->dim, set->points);
  constexpr int kQueryObjects = 64, kFramesPerObject = 4;
  for (int k = 0; k < kQueryObjects; ++k) {
    const int o = static_cast<int>(static_cast<long>(k) * objects / kQueryObjects);
    for (const QueryFrame& frame : source.Frames(o, 45.0 * (k % kSectors), kFramesPerObject)) {
      const DescriptorValues& values = frame.descriptor.values;
      set->queries.emplace_back(values.begin(), values.begin() + set->dim);
      set->query_object.push_back(o);
    }
  }
  Finish(*set);
  return set;
}

// COIL-100 described with the product's variant: views at multiples of 10 degrees make the
// model (4 or 5 per sector), the views in between are the queries.
std::unique_ptr<PointSet> CoilSet() {
  const std::filesystem::path dir = bench::DataDir() / "coil-100";
  auto set = std::make_unique<PointSet>();
  set->dim = DescriptorLength(DescriptorVariant::kCeddHsvHog);
  set->objects = 100;
  for (int n = 1; n <= 100; ++n) {
    ObjectModel model;
    model.id = n;
    model.variant = DescriptorVariant::kCeddHsvHog;
    for (int azimuth = 0; azimuth < 360; azimuth += 5) {
      const std::string file =
          (dir / ("obj" + std::to_string(n) + "__" + std::to_string(azimuth) + ".png")).string();
      const DescriptorValues values =
          ExtractCedd(ReadImageFile(file), DescriptorVariant::kCeddHsvHog).values;
      if (azimuth % 10 == 0) {
        model.views.push_back({values, static_cast<double>(azimuth), {}, 0});
      } else {
        set->queries.emplace_back(values.begin(), values.begin() + set->dim);
        set->query_object.push_back(n - 1);
      }
    }
    AddSectorMeans(model, set->dim, set->points);
  }
  Finish(*set);
  return set;
}

// "coil100" or a number of synthetic objects; built on first use and kept.
const PointSet& Set(const std::string& name) {
  static std::map<std::string, std::unique_ptr<PointSet>> sets;
  std::unique_ptr<PointSet>& set = sets[name];
  if (!set) set = name == "coil100" ? CoilSet() : SyntheticSet(std::stoi(name));
  return *set;
}

void Normalise(const float* values, int dim, float* out) {
  float norm = 0;
  for (int b = 0; b < dim; ++b) norm += values[b] * values[b];
  const float scale = norm > 0 ? 1.0f / std::sqrt(norm) : 0.0f;
  for (int b = 0; b < dim; ++b) out[b] = values[b] * scale;
}

// A nearest-neighbour index over one set's points.
class CandidateIndex {
 public:
  virtual ~CandidateIndex() = default;
  // The library's search effort: FLANN's checks, HNSW's ef, IVF's nprobe.
  virtual void SetEffort(int effort) = 0;
  // Up to c point ids nearest `query` (dim values) in the library's metric.
  virtual void Search(const float* query, int c, std::vector<std::int64_t>& ids) = 0;
  // Memory the index holds or reads, vectors included.
  virtual double Bytes() const = 0;

  double build_seconds = 0;
};

// Every point L2-normalised (a zero point stays zero): under L2 their order from a normalised
// query is cosine's.
std::vector<float> NormalisedPoints(const PointSet& set) {
  std::vector<float> unit(set.points.size());
  for (std::size_t p = 0; p < set.point_count(); ++p) {
    Normalise(set.point(p), set.dim, unit.data() + p * set.dim);
  }
  return unit;
}

class FlannKd final : public CandidateIndex {
 public:
  // On the raw means, or on L2-normalised means and queries (cosine's order).
  FlannKd(const PointSet& set, bool cosine)
      : dim_(set.dim),
        cosine_(cosine),
        unit_points_(cosine ? NormalisedPoints(set) : std::vector<float>()),
        normalised_(set.dim),
        // FLANN's matrices are not const-correct; the index only reads the points, which it
        // does not copy.
        index_(flann::Matrix<float>(
                   const_cast<float*>(cosine ? unit_points_.data() : set.points.data()),
                   set.point_count(), set.dim),
               flann::KDTreeIndexParams(4)),
        point_bytes_(set.points.size() * sizeof(float)) {
    index_.buildIndex();
  }
  void SetEffort(int checks) override { checks_ = checks; }
  void Search(const float* query, int c, std::vector<std::int64_t>& ids) override {
    indices_.resize(c);
    distances_.resize(c);
    flann::Matrix<std::size_t> index_matrix(indices_.data(), 1, c);
    flann::Matrix<float> distance_matrix(distances_.data(), 1, c);
    if (cosine_) {
      Normalise(query, dim_, normalised_.data());
      query = normalised_.data();
    }
    const flann::Matrix<float> queries(const_cast<float*>(query), 1, dim_);
    const int found =
        index_.knnSearch(queries, index_matrix, distance_matrix, c, flann::SearchParams(checks_));
    ids.assign(indices_.begin(), indices_.begin() + found);
  }
  double Bytes() const override {
    return static_cast<double>(index_.usedMemory()) + static_cast<double>(point_bytes_);
  }

 private:
  int dim_;
  bool cosine_;
  std::vector<float> unit_points_;  // cosine only: the points the index reads
  std::vector<float> normalised_;
  flann::Index<flann::L2<float>> index_;
  std::size_t point_bytes_;
  int checks_ = 32;
  std::vector<std::size_t> indices_;
  std::vector<float> distances_;
};

// Runs add(i) for i in [first, count) on every core.
template <typename Add>
void AddInParallel(std::size_t first, std::size_t count, const Add& add) {
  std::atomic<std::size_t> next{first};
  std::vector<std::thread> threads;
  for (unsigned t = 0; t < std::max(1u, std::thread::hardware_concurrency()); ++t) {
    threads.emplace_back([&] {
      for (std::size_t i = next++; i < count; i = next++) add(i);
    });
  }
  for (std::thread& thread : threads) thread.join();
}

// hnswlib through the product's wrapper (core/index/summary_graph.h): a program may include
// hnswlib's headers in one translation unit only.
class Hnsw final : public CandidateIndex {
 public:
  Hnsw(const PointSet& set, SummaryGraph::Metric metric, std::size_t build_breadth = 100)
      : graph_(set.dim, set.point_count(),
               {.metric = metric, .links = 16, .build_breadth = build_breadth}) {
    const std::size_t n = set.point_count();
    const auto add = [&](std::size_t p) { graph_.Add(set.point(p), p); };
    add(0);  // the entry point, before the threads race to link to it
    AddInParallel(1, n, add);
  }
  void SetEffort(int ef) override { graph_.SetBreadth(static_cast<std::size_t>(ef)); }
  void Search(const float* query, int c, std::vector<std::int64_t>& ids) override {
    graph_.Search(query, static_cast<std::size_t>(c), labels_);
    ids.assign(labels_.begin(), labels_.end());
  }
  double Bytes() const override { return graph_.Bytes(); }

 private:
  SummaryGraph graph_;
  std::vector<std::size_t> labels_;
};

// faiss 1.7.3 names its id type inside Index (later releases: faiss::idx_t).
using FaissId = faiss::Index::idx_t;

class FaissHnsw final : public CandidateIndex {
 public:
  // L2 on the raw means, or inner product on L2-normalised means and queries (cosine).
  FaissHnsw(const PointSet& set, bool cosine)
      : cosine_(cosine),
        index_(set.dim, 16, cosine ? faiss::METRIC_INNER_PRODUCT : faiss::METRIC_L2),
        normalised_(set.dim) {
    index_.hnsw.efConstruction = 100;
    const auto n = static_cast<FaissId>(set.point_count());
    if (cosine) {
      index_.add(n, NormalisedPoints(set).data());  // faiss keeps its own copy
    } else {
      index_.add(n, set.points.data());
    }
  }
  void SetEffort(int ef) override { index_.hnsw.efSearch = ef; }
  void Search(const float* query, int c, std::vector<std::int64_t>& ids) override {
    if (cosine_) {
      Normalise(query, index_.d, normalised_.data());
      query = normalised_.data();
    }
    distances_.resize(c);
    labels_.resize(c);
    index_.search(1, query, c, distances_.data(), labels_.data());
    ids.clear();
    for (const FaissId label : labels_) {
      if (label >= 0) ids.push_back(label);
    }
  }
  double Bytes() const override {
    const auto& storage = dynamic_cast<const faiss::IndexFlatCodes&>(*index_.storage);
    const faiss::HNSW& graph = index_.hnsw;
    return static_cast<double>(storage.codes.size()) +
           graph.neighbors.size() * sizeof(faiss::HNSW::storage_idx_t) +
           graph.offsets.size() * sizeof(std::size_t) + graph.levels.size() * sizeof(int);
  }

 private:
  bool cosine_;
  faiss::IndexHNSWFlat index_;
  std::vector<float> normalised_;
  std::vector<float> distances_;
  std::vector<FaissId> labels_;
};

class FaissIvf final : public CandidateIndex {
 public:
  explicit FaissIvf(const PointSet& set)
      : quantizer_(set.dim), index_(&quantizer_, set.dim, Lists(set.point_count())) {
    // k-means on an even sample of 64 points per list: enough for faiss, and quick.
    const std::size_t n = set.point_count();
    const std::size_t sample = std::min(n, 64 * index_.nlist);
    std::vector<float> training;
    for (std::size_t i = 0; i < sample; ++i) {
      const float* p = set.point(i * n / sample);
      training.insert(training.end(), p, p + set.dim);
    }
    index_.train(static_cast<FaissId>(sample), training.data());
    index_.add(static_cast<FaissId>(n), set.points.data());
  }
  void SetEffort(int nprobe) override { index_.nprobe = nprobe; }
  void Search(const float* query, int c, std::vector<std::int64_t>& ids) override {
    distances_.resize(c);
    labels_.resize(c);
    index_.search(1, query, c, distances_.data(), labels_.data());
    ids.clear();
    for (const FaissId label : labels_) {
      if (label >= 0) ids.push_back(label);
    }
  }
  double Bytes() const override {
    double bytes = static_cast<double>(quantizer_.codes.size());
    for (std::size_t list = 0; list < index_.nlist; ++list) {
      bytes += static_cast<double>(index_.invlists->list_size(list)) *
               (index_.code_size + sizeof(FaissId));
    }
    return bytes;
  }

 private:
  static std::size_t Lists(std::size_t points) {
    return std::max<std::size_t>(16, std::lround(std::sqrt(static_cast<double>(points))));
  }

  faiss::IndexFlatL2 quantizer_;
  faiss::IndexIVFFlat index_;
  std::vector<float> distances_;
  std::vector<FaissId> labels_;
};

std::unique_ptr<CandidateIndex> BuildIndex(const std::string& library, const PointSet& set) {
  if (library == "flann-kd") return std::make_unique<FlannKd>(set, false);
  if (library == "flann-kd-cos") return std::make_unique<FlannKd>(set, true);
  if (library == "hnsw-l2") return std::make_unique<Hnsw>(set, SummaryGraph::Metric::kEuclidean);
  if (library == "hnsw-ip") return std::make_unique<Hnsw>(set, SummaryGraph::Metric::kCosine);
  if (library == "hnsw-ip8") return std::make_unique<Hnsw>(set, SummaryGraph::Metric::kCosineBytes);
  if (library == "hnsw-ip8-b50") {
    return std::make_unique<Hnsw>(set, SummaryGraph::Metric::kCosineBytes, 50);
  }
  if (library == "faiss-hnsw") return std::make_unique<FaissHnsw>(set, false);
  if (library == "faiss-hnsw-ip") return std::make_unique<FaissHnsw>(set, true);
  return std::make_unique<FaissIvf>(set);
}

// One index at a time: the benchmarks of one library and set run one after the other (they are
// registered so), so each index is built once and the previous one's memory is returned first.
CandidateIndex& Index(const std::string& library, const std::string& set_name) {
  static std::string key;
  static std::unique_ptr<CandidateIndex> index;
  if (!index || key != library + "/" + set_name) {
    index.reset();
    const PointSet& set = Set(set_name);
    // faiss builds with an OpenMP team on every core, but searches one query with one thread:
    // a team's idle member must still reach its barrier, which costs milliseconds per query
    // when another process holds the cores.
    omp_set_num_threads(static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
    const auto start = std::chrono::steady_clock::now();
    index = BuildIndex(library, set);
    index->build_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    omp_set_num_threads(1);
    key = library + "/" + set_name;
  }
  return *index;
}

void BM_Exact(benchmark::State& state, std::string set_name) {
  const PointSet& set = Set(set_name);
  std::vector<float> tc;
  std::vector<std::pair<float, std::size_t>> best;
  std::size_t next = 0;
  for (auto _ : state) {
    ExactScan(set, set.queries[next], tc);
    const std::vector<std::size_t> top = TopObjects(tc, set.objects, kTopObjects, best);
    benchmark::DoNotOptimize(top.data());
    next = (next + 1) % set.queries.size();
  }
  state.counters["points"] = static_cast<double>(set.point_count());
  state.counters["bytes_per_point"] = (set.dim + 1) * sizeof(float);  // bin-major means, norm
}

void BM_Candidates(benchmark::State& state, std::string library, std::string set_name, int c,
                   int effort) {
  const PointSet& set = Set(set_name);
  CandidateIndex& index = Index(library, set_name);
  index.SetEffort(effort);
  // Quality over every query, untimed.
  std::vector<std::int64_t> ids;
  std::vector<std::size_t> objects;
  double recall = 0, own = 0, distinct = 0;
  for (std::size_t q = 0; q < set.queries.size(); ++q) {
    index.Search(set.queries[q].data(), c, ids);
    objects.clear();
    for (const std::int64_t id : ids) objects.push_back(static_cast<std::size_t>(id) / kSectors);
    std::sort(objects.begin(), objects.end());
    objects.erase(std::unique(objects.begin(), objects.end()), objects.end());
    const auto found = [&](std::size_t o) {
      return std::binary_search(objects.begin(), objects.end(), o);
    };
    double hits = 0;
    for (const std::size_t o : set.top[q]) hits += found(o);
    recall += hits / static_cast<double>(set.top[q].size());
    own += found(set.query_object[q]);
    distinct += static_cast<double>(objects.size());
  }
  std::size_t next = 0;
  for (auto _ : state) {
    index.Search(set.queries[next].data(), c, ids);
    benchmark::DoNotOptimize(ids.data());
    next = (next + 1) % set.queries.size();
  }
  const double queries = static_cast<double>(set.queries.size());
  state.counters["recall10"] = recall / queries;
  state.counters["own"] = own / queries;
  state.counters["objects"] = distinct / queries;
  state.counters["build_s"] = index.build_seconds;
  state.counters["bytes_per_point"] = index.Bytes() / static_cast<double>(set.point_count());
}

int RegisterCandidateBenchmarks() {
  for (const std::string set : {"1000", "10000", "100000", "coil100"}) {
    benchmark::RegisterBenchmark(("candidates/exact/" + set).c_str(), BM_Exact, set)
        ->Unit(benchmark::kMicrosecond);
    // COIL-100 has 800 points: shorter lists.
    const std::vector<int> lists =
        set == "coil100" ? std::vector<int>{16, 64} : std::vector<int>{64, 256};
    for (const std::string library : {"flann-kd", "flann-kd-cos", "hnsw-l2", "hnsw-ip", "hnsw-ip8",
                                      "hnsw-ip8-b50", "faiss-ivf", "faiss-hnsw", "faiss-hnsw-ip"}) {
      for (const int c : lists) {
        // Efforts: FLANN's checks from 2 to 32 points per candidate; HNSW's ef from C (its
        // least) to 2C; IVF's nprobe of about 1% and 4% of its lists at 100,000 objects.
        std::vector<int> efforts = {c, 2 * c};
        std::string knob = "ef";
        if (library.starts_with("flann-kd")) {
          efforts = {2 * c, 8 * c, 32 * c};
          knob = "checks";
        } else if (library == "faiss-ivf") {
          efforts = {8, 32};
          knob = "nprobe";
        }
        for (const int effort : efforts) {
          benchmark::RegisterBenchmark(
              ("candidates/" + library + "/" + set + "/" + std::to_string(c) + "/" + knob + ":" +
               std::to_string(effort))
                  .c_str(),
              BM_Candidates, library, set, c, effort)
              ->Unit(benchmark::kMicrosecond);
        }
      }
    }
  }
  return 0;
}

const int registered = RegisterCandidateBenchmarks();

}  // namespace
}  // namespace orbit
