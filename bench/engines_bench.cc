// Speed of the view index and the engines, on synthetic model sets of 100, 1000 and 10000
// objects x 72 views (and 100,000 for exact-scan and session-frame/product), plus the kd-tree's
// recall against exact search on COIL-100.
//
//   exact-scan/<objects>             one brute-force Tanimoto pass over every view
//                                    (ViewIndexSnapshot::SimilarityToEveryView);
//                                    exact-scan/<variant>/1000 the same over objects in the
//                                    product's variant
//   session-frame/<engine>/<objects> one incremental frame update with the window full (W = 8),
//                                    kd-tree index, default options; engine "product" is the
//                                    product pipeline's engine with its options (the
//                                    product's budget: at most 0.25x exact-scan/1000), and
//                                    "product-every-object" the same without object candidates
//                                    (docs/design.md#object-candidates), "product-candidates:C"
//                                    with C candidates per frame
//   session-frame/<engine>/<objects>/sessions:<n>
//                                    the same, with n sessions on the snapshot taking frames in
//                                    turn, so each frame finds its session's state out of cache
//                                    as a busy server does (BM_SessionFrames)
//   frame-after-model-change/<engine>/<objects>[/first-session]
//                                    the same, on a snapshot that gained or lost a 72-view object
//                                    since the session's previous frame (BM_FrameAfterModelChange)
//   rejection-calibration/<objects>  RejectionCalibration::FromIndex of the whole model set,
//                                    kd-tree index, one thread (the server's background
//                                    recalibration; above 1000 objects from object candidates)
//   rejection-calibration-every-object/<objects>
//                                    the same, every left-out object scored against every object
//                                    (the reference the candidates are measured by)
//   catalogue-confidence/<objects>   one update's confidence from the calibration of the model
//                                    set (CatalogueConfidence, core/decision/confidence.h), at
//                                    U spread over the null's and the known windows' range, n = 8;
//                                    fitted-confidence the logistic it replaces, for scale
//   kd-search/coil100, exact-search/coil100
//                                    one retrieval list (N_L = 4) over COIL-100's views at
//                                    multiples of 10 degrees, queried with the views in between;
//                                    the kd-tree reports recall@4 against exact search
//
// The synthetic objects are bench/synthetic_objects.h's: in the product's variant for the product
// and its relatives (BenchVariant), CEDD alone for the thesis' engines and the scans. Queries
// are views 2.5 degrees off the model views. Everything is seeded: every run sees the same sets.
//
// Run: build/orbit_bench --benchmark_filter='exact-scan|session-frame|coil100'
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "bench/bench_data.h"
#include "bench/synthetic_objects.h"
#include "client/image_file.h"
#include "core/base/parallel_for.h"
#include "core/decision/confidence.h"
#include "core/decision/rejection_calibration.h"
#include "core/descriptor/cedd.h"
#include "core/engines/engine_registry.h"
#include "core/engines/product_pipeline.h"
#include "core/engines/recognition_engine.h"
#include "core/engines/sector_similarity_table.h"
#include "core/index/view_index.h"

namespace orbit {
namespace {

using bench::SyntheticObjects;

struct SyntheticSet {
  std::unique_ptr<SyntheticObjects> objects;
  std::unique_ptr<ViewIndex> index;
};

// Built once per size, mode and variant, on first use.
SyntheticSet& Synthetic(int objects, SearchMode mode,
                        DescriptorVariant variant = DescriptorVariant::kCeddLire) {
  static std::map<std::tuple<int, SearchMode, DescriptorVariant>, SyntheticSet> sets;
  // Two sets of 100,000 objects do not fit this machine's memory together: a large set is
  // dropped when another one is asked for (and built again if it is asked for later).
  constexpr int kLargeSet = 10000;
  if (objects > kLargeSet && !sets.contains({objects, mode, variant})) {
    std::erase_if(sets, [](const auto& entry) { return std::get<0>(entry.first) > kLargeSet; });
  }
  SyntheticSet& set = sets[{objects, mode, variant}];
  if (!set.index) {
    set.objects = std::make_unique<SyntheticObjects>(objects, variant);
    // Loaded on every CPU, as a server loads its store (only sets above 1000 objects differ).
    set.index = std::make_unique<ViewIndex>(
        set.objects->Models(), ViewIndexOptions{.search = mode, .build_threads = AvailableCpus()});
  }
  return set;
}

void BM_ExactScan(benchmark::State& state, int objects, DescriptorVariant variant) {
  SyntheticSet& set = Synthetic(objects, SearchMode::kExact, variant);
  const auto snapshot = set.index->Snapshot();
  const DescriptorValues query = set.objects->View(objects / 2, 102.5);
  std::vector<float> similarities;
  for (auto _ : state) {
    snapshot->SimilarityToEveryView(query, similarities);
    benchmark::DoNotOptimize(similarities.data());
  }
  state.counters["views"] = static_cast<double>(snapshot->view_count());
}

// The calibrated rejection rule's calibration of the whole model set (what the server redoes in
// the background after each enrollment).
void BM_RejectionCalibration(benchmark::State& state, int objects, bool every_object) {
  SyntheticSet& set = Synthetic(objects, SearchMode::kKdTree);
  const auto snapshot = set.index->Snapshot();
  CalibrationOptions options;
  if (every_object) options.scan_every_object_up_to = snapshot->object_count();
  for (auto _ : state) {
    const RejectionCalibration calibration = RejectionCalibration::FromIndex(*snapshot, options);
    benchmark::DoNotOptimize(calibration.NullThreshold(8, 0.15));
    state.counters["sampled_views"] = calibration.sampled_views();
    // The thresholds, to compare the candidates with the every-object reference.
    state.counters["threshold_n1"] = calibration.NullThreshold(1, 0.17);
    state.counters["threshold_n8"] = calibration.NullThreshold(8, 0.17);
  }
}

// One update's confidence, at 64 statistics spread from the known windows' least to the null's
// largest, cycled through.
void BM_CatalogueConfidence(benchmark::State& state, int objects) {
  SyntheticSet& set = Synthetic(objects, SearchMode::kKdTree);
  const RejectionCalibration calibration = RejectionCalibration::FromIndex(*set.index->Snapshot());
  constexpr int kFrames = 8;
  const auto known = calibration.KnownWindows(kFrames);
  const auto null = calibration.NullWindows(kFrames);
  if (known.empty()) {
    state.SkipWithError("no known windows");
    return;
  }
  std::vector<double> statistics;
  for (int i = 0; i < 64; ++i) {
    statistics.push_back(known.front() + (null.back() - known.front()) * i / 63.0);
  }
  std::size_t next = 0;
  for (auto _ : state) {
    const double u = statistics[next++ % statistics.size()];
    benchmark::DoNotOptimize(CatalogueConfidence(calibration, u, u, kFrames));
  }
}

void BM_FittedConfidence(benchmark::State& state) {
  std::size_t next = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(Confidence(0.5 + 0.03 * static_cast<double>(next++ % 64), 8));
  }
}

// The variant of the synthetic objects engine `name` runs on: the product's own for the product
// pipeline and its variants ("product", "product-every-object", "product-candidates:C"), as a
// server of a store made by default holds them; CEDD alone for the thesis' engines.
DescriptorVariant BenchVariant(const std::string& name) {
  return name.starts_with(kProductMethod) ? Product().variant : DescriptorVariant::kCeddLire;
}

// The engine called `name` with its default options; for "product" the product pipeline's
// engine with its options (core/engines/product_pipeline.h); for
// "product-every-object" the same scoring every object at any catalogue size
// (candidate_objects 0), the reference that shows what the candidates save.
std::unique_ptr<RecognitionEngine> BenchEngine(const std::string& name) {
  if (name == kProductMethod) return CreateEngine(Product().engine, Product().options);
  if (name == "product-every-object") {
    EngineOptions options = Product().options;
    options.candidate_objects = 0;
    return CreateEngine(Product().engine, options);
  }
  if (name.starts_with("product-candidates:")) {
    EngineOptions options = Product().options;
    options.candidate_objects = std::stoi(name.substr(name.find(':') + 1));
    options.candidates_above = 0;
    return CreateEngine(Product().engine, options);
  }
  return CreateEngine(name);
}

void BM_SessionFrame(benchmark::State& state, std::string engine_name, int objects) {
  SyntheticSet& set = Synthetic(objects, SearchMode::kKdTree, BenchVariant(engine_name));
  const auto snapshot = set.index->Snapshot();
  const auto engine = BenchEngine(engine_name);
  const int window = engine->options().window;
  // Frames of a few objects, cycled: the window is full before timing starts.
  std::vector<QueryFrame> frames;
  for (int o = 0; o < 4; ++o) {
    for (const QueryFrame& f : set.objects->Frames(o * objects / 4, 40.0 * o, 2 * window)) {
      frames.push_back(f);
    }
  }
  for (int k = 0; k < window; ++k) engine->Observe(snapshot, frames[k]);
  std::size_t next = window;
  int correct = 0, answered = 0;
  for (auto _ : state) {
    const FrameUpdate update = engine->Observe(snapshot, frames[next]);
    benchmark::DoNotOptimize(update.ranking.data());
    state.PauseTiming();
    const int truth = static_cast<int>(next / (2 * window)) * objects / 4 + 1;
    correct += !update.ranking.empty() && update.ranking[0].object == truth;
    ++answered;
    next = (next + 1) % frames.size();
    state.ResumeTiming();
  }
  state.counters["top1"] = answered > 0 ? static_cast<double>(correct) / answered : 0;
}

// One frame each of `sessions` sessions in turn, windows full: what a frame costs when many
// sessions share the server, their per-frame state evicted from the caches by the others'.
void BM_SessionFrames(benchmark::State& state, std::string engine_name, int objects, int sessions) {
  SyntheticSet& set = Synthetic(objects, SearchMode::kKdTree, BenchVariant(engine_name));
  const auto snapshot = set.index->Snapshot();
  std::vector<std::unique_ptr<RecognitionEngine>> engines;
  for (int s = 0; s < sessions; ++s) engines.push_back(BenchEngine(engine_name));
  const int window = engines.front()->options().window;
  const std::vector<QueryFrame> frames = set.objects->Frames(objects / 3, 25.0, 4 * window);
  for (const auto& engine : engines) {
    for (int k = 0; k < window; ++k) engine->Observe(snapshot, frames[k]);
  }
  std::size_t next = window, turn = 0;
  for (auto _ : state) {
    const FrameUpdate update = engines[turn]->Observe(snapshot, frames[next]);
    benchmark::DoNotOptimize(update.ranking.data());
    if (++turn == engines.size()) {
      turn = 0;
      next = next + 1 < frames.size() ? next + 1 : window;
    }
  }
}

// One frame of a session whose window is full, on a snapshot that differs from its previous
// frame's by one enrolled (even iterations) or deleted (odd) object of 72 views: what an
// enrollment costs each open session. `shared_work_done` builds the
// snapshot's shared state first (the HMM's sector table, built once per snapshot by the first
// session to see it), as for every session but one; otherwise the session pays for it.
void BM_FrameAfterModelChange(benchmark::State& state, std::string engine_name, int objects,
                              bool shared_work_done) {
  struct ChangingSet {
    std::unique_ptr<SyntheticObjects> source;
    std::unique_ptr<ViewIndex> index;
    ObjectModel enrolled;  // enrolled and deleted in turn
  };
  static std::map<std::pair<int, DescriptorVariant>, ChangingSet> sets;
  const DescriptorVariant variant = BenchVariant(engine_name);
  ChangingSet& set = sets[{objects, variant}];
  if (!set.index) {
    set.source = std::make_unique<SyntheticObjects>(objects + 1, variant);
    std::vector<ObjectModel> models = set.source->Models();
    set.enrolled = std::move(models.back());
    models.pop_back();
    set.index = std::make_unique<ViewIndex>(std::move(models),
                                            ViewIndexOptions{.search = SearchMode::kKdTree});
  }
  const std::unique_ptr<ViewIndex>& index = set.index;
  const ObjectModel& enrolled = set.enrolled;
  SyntheticObjects* const source = set.source.get();
  const auto engine = BenchEngine(engine_name);
  const int window = engine->options().window;
  const std::vector<QueryFrame> frames = source->Frames(0, 0.0, 4 * window);
  for (int k = 0; k < window; ++k) engine->Observe(index->Snapshot(), frames[k]);
  std::size_t next = window;
  bool present = false;
  std::shared_ptr<const ViewIndexSnapshot> previous = index->Snapshot();
  for (auto _ : state) {
    state.PauseTiming();
    if (present) {
      index->Remove(enrolled.id);
    } else {
      index->Add(enrolled);
    }
    present = !present;
    const auto snapshot = index->Snapshot();
    // What the first session on a snapshot computes for all of them: the change since the
    // previous snapshot and, for the HMM, the sector table.
    if (shared_work_done) {
      benchmark::DoNotOptimize(snapshot->ChangeSince(*previous));
      if (engine->name() == "hmm") {
        benchmark::DoNotOptimize(
            SectorSimilarityTable::Of(*snapshot, engine->options().hmm_states));
      }
    }
    previous = snapshot;
    state.ResumeTiming();
    const FrameUpdate update = engine->Observe(snapshot, frames[next]);
    benchmark::DoNotOptimize(update.ranking.data());
    next = next + 1 < frames.size() ? next + 1 : window;
  }
  if (present) index->Remove(enrolled.id);
}

// COIL-100 descriptors (cedd-lire), extracted on first use: views at multiples of 10 degrees as
// the model, the others as queries.
struct CoilSplit {
  std::vector<ObjectModel> models;
  std::vector<DescriptorValues> queries;
};

const CoilSplit& Coil() {
  static const CoilSplit split = [] {
    const std::filesystem::path dir = bench::DataDir() / "coil-100";
    CoilSplit s;
    for (int n = 1; n <= 100; ++n) {
      ObjectModel model;
      model.id = n;
      model.name = "obj" + std::to_string(n);
      for (int azimuth = 0; azimuth < 360; azimuth += 5) {
        const std::string file =
            (dir / ("obj" + std::to_string(n) + "__" + std::to_string(azimuth) + ".png")).string();
        const DescriptorValues values =
            ExtractCedd(ReadImageFile(file), DescriptorVariant::kCeddLire).values;
        if (azimuth % 10 == 0) {
          model.views.push_back({values, static_cast<double>(azimuth), {}, 0});
        } else {
          s.queries.push_back(values);
        }
      }
      s.models.push_back(std::move(model));
    }
    return s;
  }();
  return split;
}

void BM_CoilSearch(benchmark::State& state, SearchMode mode) {
  const CoilSplit& coil = Coil();
  static std::map<SearchMode, std::unique_ptr<ViewIndex>> indexes;
  auto& index = indexes[mode];
  if (!index) index = std::make_unique<ViewIndex>(coil.models, ViewIndexOptions{.search = mode});
  const auto snapshot = index->Snapshot();
  // Recall@4 against exact search, over every query.
  long found = 0;
  for (const DescriptorValues& q : coil.queries) {
    std::set<std::pair<ObjectId, int>> truth;
    for (const ViewMatch& m : snapshot->SearchExact(q, 4)) truth.insert({m.object, m.view});
    for (const ViewMatch& m : snapshot->Search(q, 4)) found += truth.count({m.object, m.view});
  }
  std::size_t next = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(snapshot->Search(coil.queries[next], 4).data());
    next = (next + 1) % coil.queries.size();
  }
  state.counters["recall@4"] = static_cast<double>(found) / (4.0 * coil.queries.size());
}

int RegisterEngineBenchmarks() {
  // 100,000 objects (7.2 million views) only where the set fits this machine's memory: the
  // exact scan and the product, which never builds the view kd-trees (docs/design.md#view-index).
  for (const int objects : {100, 1000, 10000, 100000}) {
    benchmark::RegisterBenchmark(("exact-scan/" + std::to_string(objects)).c_str(), BM_ExactScan,
                                 objects, DescriptorVariant::kCeddLire)
        ->Unit(benchmark::kMicrosecond);
  }
  // The product's budget against a scan of views in its own variant.
  benchmark::RegisterBenchmark(
      ("exact-scan/" + std::string(VariantName(Product().variant)) + "/1000").c_str(), BM_ExactScan,
      1000, Product().variant)
      ->Unit(benchmark::kMicrosecond);
  for (const int objects : {100, 1000, 2000, 10000}) {
    benchmark::RegisterBenchmark(("rejection-calibration/" + std::to_string(objects)).c_str(),
                                 BM_RejectionCalibration, objects, false)
        ->Unit(benchmark::kMillisecond);
  }
  benchmark::RegisterBenchmark("rejection-calibration-every-object/2000", BM_RejectionCalibration,
                               2000, true)
      ->Unit(benchmark::kMillisecond);
  for (const int objects : {100, 1000}) {
    benchmark::RegisterBenchmark(("catalogue-confidence/" + std::to_string(objects)).c_str(),
                                 BM_CatalogueConfidence, objects)
        ->Unit(benchmark::kMicrosecond);
  }
  benchmark::RegisterBenchmark("fitted-confidence", BM_FittedConfidence)
      ->Unit(benchmark::kMicrosecond);
  for (const char* engine :
       {"vci", "hmm", "product", "product-every-object", "product-candidates:8",
        "product-candidates:16", "product-candidates:32"}) {
    for (const int objects : {100, 1000, 10000, 100000}) {
      if (objects == 100000 && std::string(engine) != "product") continue;
      benchmark::RegisterBenchmark(
          ("session-frame/" + std::string(engine) + "/" + std::to_string(objects)).c_str(),
          BM_SessionFrame, std::string(engine), objects)
          ->Unit(benchmark::kMicrosecond);
    }
  }
  for (const char* engine : {"vci", "hmm", "product"}) {
    for (const int sessions : {8, 64, 256}) {
      if (sessions != 64 && std::string(engine) != "product") continue;
      benchmark::RegisterBenchmark(
          ("session-frame/" + std::string(engine) + "/1000/sessions:" + std::to_string(sessions))
              .c_str(),
          BM_SessionFrames, std::string(engine), 1000, sessions)
          ->Unit(benchmark::kMicrosecond);
    }
  }
  for (const char* engine : {"vci", "hmm", "product", "product-candidates:8"}) {
    for (const int objects : {100, 1000}) {
      for (const bool shared : {true, false}) {
        benchmark::RegisterBenchmark(("frame-after-model-change/" + std::string(engine) + "/" +
                                      std::to_string(objects) + (shared ? "" : "/first-session"))
                                         .c_str(),
                                     BM_FrameAfterModelChange, std::string(engine), objects, shared)
            ->Unit(benchmark::kMicrosecond);
        if (std::string(engine) == "vci") break;  // only the HMM has shared per-snapshot work
      }
    }
  }
  benchmark::RegisterBenchmark("exact-search/coil100", BM_CoilSearch, SearchMode::kExact)
      ->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark("kd-search/coil100", BM_CoilSearch, SearchMode::kKdTree)
      ->Unit(benchmark::kMicrosecond);
  return 0;
}

const int registered = RegisterEngineBenchmarks();

}  // namespace
}  // namespace orbit
