// Model store speed: what a server start-up costs (open + LoadAll of 1000 objects x 72 views,
// and the view index built from it) and what one durable enrollment costs (one transaction,
// synchronous=FULL).
//
// The store is built once per run in the system's temp folder (1000 enrollments, a few seconds),
// and removed at exit. Loads run with the file in the OS page cache, as on a server restart.
// Run: build/orbit_bench --benchmark_filter='store-'
#include <benchmark/benchmark.h>

#include <unistd.h>

#include <filesystem>
#include <map>
#include <random>
#include <string>

#include "core/index/view_index.h"
#include "storage/sqlite_model_store.h"
#include "storage/view_index_loading.h"

namespace orbit {
namespace {

constexpr int kViewsPerObject = 72;

// An object of kViewsPerObject views 5 degrees apart, random descriptor values in 0..7.
Enrollment RandomObject(const std::string& name, std::mt19937& random) {
  std::uniform_int_distribution<int> value(0, kDescriptorMaxValue);
  Enrollment enrollment;
  enrollment.name = name;
  for (int f = 0; f < kViewsPerObject; ++f) {
    ModelView view;
    for (std::uint8_t& v : view.descriptor) v = static_cast<std::uint8_t>(value(random));
    view.azimuth = 5.0 * f;
    view.typical_distance = 0.1;
    enrollment.views.push_back(view);
  }
  return enrollment;
}

// A scratch folder removed at exit.
class BenchDir {
 public:
  BenchDir()
      : path_(std::filesystem::temp_directory_path() /
              ("orbit_store_bench_" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(path_);
  }
  ~BenchDir() { std::filesystem::remove_all(path_); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// The store of `objects` random objects, built on first use.
const std::filesystem::path& StoreOf(int objects) {
  static BenchDir dir;
  static std::map<int, std::filesystem::path> built;
  auto [found, is_new] =
      built.try_emplace(objects, dir.path() / ("load-" + std::to_string(objects) + ".db"));
  if (is_new) {
    SqliteModelStore store(found->second, {.create_if_missing = true});
    std::mt19937 random(12345);
    for (int i = 0; i < objects; ++i) store.Enroll(RandomObject("obj" + std::to_string(i), random));
  }
  return found->second;
}

// Start-up: open (quick_check, schema check) and load every object with its views.
void BM_StoreLoad(benchmark::State& state) {
  const int objects = static_cast<int>(state.range(0));
  const std::filesystem::path& file = StoreOf(objects);
  for (auto _ : state) {
    SqliteModelStore store(file);
    const std::vector<ObjectModel> models = store.LoadAll();
    if (models.size() != static_cast<std::size_t>(objects)) state.SkipWithError("wrong count");
    benchmark::DoNotOptimize(models.data());
  }
  state.counters["views"] = objects * kViewsPerObject;
  state.SetItemsProcessed(state.iterations() * objects * kViewsPerObject);
}

// LoadAll alone, on a store already open.
void BM_StoreLoadAllOpen(benchmark::State& state) {
  const int objects = static_cast<int>(state.range(0));
  SqliteModelStore store(StoreOf(objects));
  for (auto _ : state) benchmark::DoNotOptimize(store.LoadAll().data());
  state.SetItemsProcessed(state.iterations() * objects * kViewsPerObject);
}

// Start-up up to a searchable index: open, LoadAll, one-pass ViewIndex build (LoadViewIndex).
void BM_StoreLoadIndex(benchmark::State& state, SearchMode mode) {
  const int objects = static_cast<int>(state.range(0));
  const std::filesystem::path& file = StoreOf(objects);
  for (auto _ : state) {
    SqliteModelStore store(file);
    benchmark::DoNotOptimize(LoadViewIndex(store, DescriptorVariant::kCeddLire, {.search = mode}));
  }
}

// The alternative LoadViewIndex avoids: the same objects added to the index one by one.
void BM_IndexAddLoop(benchmark::State& state, SearchMode mode) {
  const int objects = static_cast<int>(state.range(0));
  SqliteModelStore store(StoreOf(objects));
  const std::vector<ObjectModel> models = store.LoadAll();
  for (auto _ : state) {
    ViewIndex index(DescriptorVariant::kCeddLire, {.search = mode});
    for (const ObjectModel& model : models) index.Add(model);
  }
}

// One durable enrollment of a 72-view object (and its deletion, untimed, to keep the store
// small): the latency a client waits for OK.
void BM_StoreEnroll(benchmark::State& state) {
  static BenchDir dir;
  SqliteModelStore store(dir.path() / "enroll.db", {.create_if_missing = true});
  std::mt19937 random(7);
  const Enrollment object = RandomObject("mug", random);
  for (auto _ : state) {
    const ObjectId id = store.Enroll(object);
    state.PauseTiming();
    store.Delete(id);
    state.ResumeTiming();
  }
}

BENCHMARK(BM_StoreLoad)->Name("store-load")->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StoreLoadAllOpen)
    ->Name("store-loadall-open")
    ->Arg(1000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_StoreLoadIndex, exact, SearchMode::kExact)
    ->Name("store-load-index-exact")
    ->Arg(1000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_StoreLoadIndex, kdtree, SearchMode::kKdTree)
    ->Name("store-load-index-kdtree")
    ->Arg(1000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_IndexAddLoop, kdtree, SearchMode::kKdTree)
    ->Name("index-add-loop-kdtree")
    ->Arg(1000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StoreEnroll)->Name("store-enroll/72")->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace orbit
