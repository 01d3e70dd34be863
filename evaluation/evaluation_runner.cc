#include "evaluation/evaluation_runner.h"

#include <malloc.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/base/angles.h"
#include "core/base/mutex.h"
#include "core/base/parallel_for.h"
#include "core/base/seeded_random.h"
#include "core/decision/rejection_calibration.h"
#include "core/descriptor/cedd.h"
#include "core/descriptor/view_description.h"
#include "core/engines/product_pipeline.h"
#include "evaluation/distractor_objects.h"

// gperftools' malloc_extension_c.h, when tcmalloc is linked (HeapBytesInUse).
extern "C" int MallocExtension_GetNumericProperty(const char* property, std::size_t* value)
    __attribute__((weak));

namespace orbit {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Bytes the allocator has handed out and not taken back. Its growth across a single-threaded
// step is the heap memory that step kept. `orbit` links tcmalloc (cmake/OrbitDeps.cmake,
// ORBIT_TCMALLOC), whose heap glibc's mallinfo2 does not see: ask tcmalloc when it is linked
// (its C interface, declared weak so that a program without it links too), else glibc (arena
// and mmapped blocks).
std::size_t HeapBytesInUse() {
  std::size_t allocated = 0;
  if (MallocExtension_GetNumericProperty != nullptr &&
      MallocExtension_GetNumericProperty("generic.current_allocated_bytes", &allocated) != 0) {
    return allocated;
  }
  const struct mallinfo2 info = ::mallinfo2();
  return info.uordblks + info.hblkhd;
}

// ParallelFor with the options' progress callback for `stage`.
void RunStage(std::size_t count, int threads, std::string_view stage,
              const EvaluationOptions& options, const std::function<void(std::size_t)>& task) {
  ParallelFor(count, threads, task, [&](std::size_t done) {
    if (options.progress) options.progress(stage, done, count);
  });
}

// The variant method `name` is always evaluated on, added to the run's when it lacks it (the
// product's own), or none: a thesis' engine runs on every variant of the run.
std::optional<DescriptorVariant> OwnVariant(std::string_view name) {
  if (name == kProductMethod) return Product().variant;
  return std::nullopt;
}

// A method as the runner runs it: an engine with its options (the variants it is measured on:
// Evaluates).
struct Method {
  std::string_view engine;  // one of EngineNames()
  EngineOptions options;
};

// The method called `name` on descriptors of `variant` in a run whose engines take `run`: an
// engine of EngineNames() with `run`, or kProductMethod, the product pipeline
// (core/engines/product_pipeline.h): its engine with its own options, the window raised, the
// known-accept rate set as the run's, the false-accept rate `product_rate` or, unset, the
// variant's own (ProductFalseAcceptRate, as a server on a store in `variant` takes it), and the
// run's object candidates when it sets them (candidate_objects > 0).
// Throws std::invalid_argument for any other name.
Method ResolveMethod(std::string_view name, const EngineOptions& run, DescriptorVariant variant,
                     std::optional<double> product_rate) {
  if (name != kProductMethod) return {FindEngine(name).name, run};
  EngineOptions options = Product().options;
  options.window = std::max(options.window, run.window);
  options.false_accept_rate = product_rate.value_or(ProductFalseAcceptRate(variant));
  options.known_accept_rate = run.known_accept_rate;
  if (run.candidate_objects > 0) {
    options.candidate_objects = run.candidate_objects;
    options.candidates_above = run.candidates_above;
  }
  return {Product().engine, options};
}

// Throws std::invalid_argument for options out of range or no known image (RunEvaluation's
// contract).
void ValidateOptions(const std::vector<DatasetImage>& known, const EvaluationOptions& options) {
  const auto require = [](bool ok, const std::string& message) {
    if (!ok) throw std::invalid_argument(message);
  };
  require(!known.empty(), "no images of known objects to evaluate");
  require(!options.variants.empty(), "no descriptor variant");
  require(!options.methods.empty(), "no method");
  require(!options.distortions.empty(), "no distortion");
  require(!options.query_lengths.empty(), "no query length n");
  const auto names = EngineNames();
  for (const std::string& method : options.methods) {
    require(
        method == kProductMethod || std::find(names.begin(), names.end(), method) != names.end(),
        "unknown method \"" + method + "\"");
  }
  for (int n : options.query_lengths) {
    require(n >= 1 && n <= kMaxWindow,
            "n = " + std::to_string(n) + " is outside 1.." + std::to_string(kMaxWindow));
  }
  require(options.trials >= 1, "trials must be at least 1");
  require(options.threads >= 0, "threads must be >= 0");
  require(options.distractors >= 0 && options.distractors <= kMaxDistractors,
          "distractors must be in 0.." + std::to_string(kMaxDistractors) + ", got " +
              std::to_string(options.distractors));
  ValidateEngineOptions(options.engine);
  if (options.product_false_accept_rate) {
    EngineOptions product = options.engine;
    product.false_accept_rate = *options.product_false_accept_rate;
    ValidateEngineOptions(product, "product ");
  }
  ViewIndex probe(options.variants.front(), options.index);  // validates the index options
}

// `options` with its methods' own variants (the product's) added, last, when `variants` lacks
// them.
EvaluationOptions WithProductVariant(EvaluationOptions options) {
  for (const std::string& method : options.methods) {
    const std::optional<DescriptorVariant> own = OwnVariant(method);
    if (own && std::find(options.variants.begin(), options.variants.end(), *own) ==
                   options.variants.end()) {
      options.variants.push_back(*own);
    }
  }
  return options;
}

// The longest query, n. REQUIRES: options.query_lengths is not empty (ValidateOptions).
int LargestN(const EvaluationOptions& options) {
  return *std::max_element(options.query_lengths.begin(), options.query_lengths.end());
}

// A report with what `options` say filled in: seed, search, orientation, index, threads and
// the engines' options with the window raised to the longest query.
EvaluationReport ReportOf(const EvaluationOptions& options) {
  EvaluationReport report;
  report.seed = options.seed;
  report.search = options.index.search;
  report.use_orientation = options.use_orientation;
  report.active_step = options.active_step;
  report.active_policy = options.active_policy;
  report.index = options.index;
  report.threads = options.threads > 0 ? options.threads : AvailableCpus();
  report.engine = options.engine;
  report.engine.window = std::max(report.engine.window, LargestN(options));
  return report;
}

// The evaluated images and their objects. Images: the known ones, then the unknown ones.
// Objects are numbered the same way (known ones first), each in order of first appearance; the
// known object numbered o has the model id o + 1.
struct EvaluationDataset {
  std::vector<const DatasetImage*> images;
  std::vector<DatasetObject> known;    // image positions into `images`
  std::vector<DatasetObject> unknown;  // image positions into `images`

  std::size_t object_count() const { return known.size() + unknown.size(); }
  bool is_known(std::size_t object) const { return object < known.size(); }
  const DatasetObject& object(std::size_t object) const {
    return is_known(object) ? known[object] : unknown[object - known.size()];
  }
};

// Validates the options and the dataset and groups the images by object; throws
// std::invalid_argument as RunEvaluation documents.
EvaluationDataset ValidateAndGroup(const std::vector<DatasetImage>& known,
                                   const std::vector<DatasetImage>& unknown,
                                   const EvaluationOptions& options) {
  ValidateOptions(known, options);
  EvaluationDataset dataset;
  dataset.known = GroupByObject(known);
  dataset.unknown = GroupByObject(unknown);
  for (DatasetObject& object : dataset.unknown) {
    for (std::size_t& image : object.images) image += known.size();
  }
  const int max_n = LargestN(options);
  for (const auto& group : {&dataset.known, &dataset.unknown}) {
    for (const DatasetObject& object : *group) {
      if (static_cast<int>(object.images.size()) < max_n) {
        throw std::invalid_argument("object \"" + object.name + "\" has " +
                                    std::to_string(object.images.size()) +
                                    " views; n = " + std::to_string(max_n) + " needs as many");
      }
    }
  }
  for (const DatasetObject& object : dataset.unknown) {
    if (std::any_of(dataset.known.begin(), dataset.known.end(),
                    [&](const DatasetObject& k) { return k.name == object.name; })) {
      throw std::invalid_argument("object \"" + object.name + "\" is both known and unknown");
    }
  }
  for (const DatasetImage& image : known) dataset.images.push_back(&image);
  for (const DatasetImage& image : unknown) dataset.images.push_back(&image);
  return dataset;
}

// Every image described in every variant: [image][variant].
using DescribedImages = std::vector<std::vector<DescribedImage>>;

// Step 1: DescribeImage of every image, on `threads` threads.
DescribedImages DescribeImages(const EvaluationDataset& dataset, const EvaluationOptions& options,
                               int threads) {
  DescribedImages described(dataset.images.size());
  RunStage(described.size(), threads, "descriptors", options, [&](std::size_t i) {
    described[i] =
        DescribeImage(*dataset.images[i], i, options.variants, options.distortions, options.seed);
  });
  return described;
}

// The model set of one variant.
struct VariantModels {
  std::vector<ObjectModel> models;  // one per known object, ids = positions + 1
  // The distractors' index (EvaluationOptions::distractors; null for none), which the full index
  // and every trial's extend with the known objects (ViewIndexSnapshot::With).
  std::shared_ptr<const ViewIndexSnapshot> distractors;
  // The index of all of them, which unknown objects are queried against (immutable, shared by
  // all threads).
  std::shared_ptr<const ViewIndexSnapshot> full_index;
  // The calibrated rejection rule's null distributions, from the full index (a trial's index
  // lacks a few views of one object: the calibration barely moves, and is computed once).
  std::shared_ptr<const RejectionCalibration> calibration;
  ModelMemory memory;
};

// The distractors `options.distractor_models` gives for `variant`, numbered from `first_id`.
// Throws std::invalid_argument when it gives another count or another variant.
std::vector<ObjectModel> GivenDistractors(const EvaluationOptions& options,
                                          DescriptorVariant variant, ObjectId first_id) {
  std::vector<ObjectModel> models = options.distractor_models(options.distractors, variant);
  if (models.size() != static_cast<std::size_t>(options.distractors)) {
    throw std::invalid_argument(options.distractors_from + " gave " +
                                std::to_string(models.size()) + " distractors, not " +
                                std::to_string(options.distractors));
  }
  for (std::size_t k = 0; k < models.size(); ++k) {
    if (models[k].variant != variant) {
      throw std::invalid_argument(options.distractors_from + " gave a distractor in " +
                                  std::string(VariantName(models[k].variant)) + ", not " +
                                  std::string(VariantName(variant)));
    }
    models[k].id = first_id + static_cast<ObjectId>(k);
  }
  return models;
}

// Step 2: for each variant (in the options' order), the distractors (on `threads` threads), the
// known objects' models made of their images' model views, then the full index and its memory
// (the known objects' alone), and its calibration (on `threads` threads). The index is built on
// one thread, so the heap growth across its construction is that index's memory.
std::vector<VariantModels> BuildModels(const EvaluationDataset& dataset,
                                       const DescribedImages& described,
                                       const EvaluationOptions& options, int threads) {
  std::vector<VariantModels> variants(options.variants.size());
  for (std::size_t v = 0; v < variants.size() && options.distractors > 0; ++v) {
    const auto progress = [&](int done, int count) {
      if (options.progress) {
        options.progress("distractors", v * static_cast<std::size_t>(count) + done,
                         variants.size() * static_cast<std::size_t>(count));
      }
    };
    const auto first_id = static_cast<ObjectId>(dataset.known.size() + 1);
    variants[v].distractors =
        ViewIndex(options.distractor_models
                      ? GivenDistractors(options, options.variants[v], first_id)
                      : MakeDistractors(options.distractors, options.variants[v], first_id,
                                        options.seed, threads, progress),
                  options.index)
            .Snapshot();
  }
  for (std::size_t v = 0; v < variants.size(); ++v) {
    for (std::size_t o = 0; o < dataset.known.size(); ++o) {
      ObjectModel model;
      model.id = static_cast<ObjectId>(o + 1);
      model.name = dataset.known[o].name;
      model.variant = options.variants[v];
      for (std::size_t i : dataset.known[o].images) model.views.push_back(described[i][v].view);
      variants[v].models.push_back(std::move(model));
    }
  }
  for (std::size_t v = 0; v < variants.size(); ++v) {
    ModelMemory& memory = variants[v].memory;
    memory.variant = options.variants[v];
    memory.objects = variants[v].models.size();
    for (const ObjectModel& model : variants[v].models) memory.views += model.views.size();
    memory.descriptor_bytes = memory.views * kDescriptorSize;
    const std::size_t before = HeapBytesInUse();
    variants[v].full_index = variants[v].distractors
                                 ? variants[v].distractors->With(variants[v].models)
                                 : ViewIndex(variants[v].models, options.index).Snapshot();
    const std::size_t after = HeapBytesInUse();
    memory.index_bytes = after > before ? after - before : 0;
    variants[v].calibration = std::make_shared<const RejectionCalibration>(
        RejectionCalibration::FromIndex(*variants[v].full_index, {.threads = threads}));
  }
  return variants;
}

// The tasks of step 3, one per (variant, object, n, trial) in that nesting order, and where
// their outcomes lie in the flat outcome table: [task][distortion][method].
struct TrialGrid {
  struct Task {
    std::size_t variant = 0;
    std::size_t object = 0;  // EvaluationDataset's numbering
    std::size_t n_slot = 0;  // position in the options' query lengths
    std::size_t trial = 0;
  };

  std::size_t variants = 0, objects = 0, ns = 0, trials = 0, distortions = 0, methods = 0;

  std::size_t task_count() const { return variants * objects * ns * trials; }
  std::size_t outcome_count() const { return task_count() * distortions * methods; }
  std::size_t TaskNumber(const Task& t) const {
    return ((t.variant * objects + t.object) * ns + t.n_slot) * trials + t.trial;
  }
  Task TaskAt(std::size_t task) const {
    return {task / trials / ns / objects, (task / trials / ns) % objects, (task / trials) % ns,
            task % trials};
  }
  std::size_t OutcomeSlot(std::size_t task, std::size_t d, std::size_t m) const {
    return (task * distortions + d) * methods + m;
  }
};

// One method's answer to one query.
struct Outcome {
  bool answered = false;  // false: the task asked nothing (a capture shorter than its n)
  QueryVerdict verdict;
  double seconds = 0;  // wall-clock time in ObserveSequence
};

// The outcome of `update` for a query of `object` whose right answer is object `expected`, or
// kUnknown when `expected` is 0 (an object outside the model set), answered from `model_set`
// (its objects' names: the dataset's and the distractors'). `true_azimuth`: the model azimuth the
// latest frame was taken at, when known (the protocol's views), for the pose error.
void Judge(const FrameUpdate& update, const ViewIndexSnapshot& model_set, const std::string& object,
           ObjectId expected, std::optional<double> true_azimuth, Outcome& outcome) {
  QueryVerdict& verdict = outcome.verdict;
  verdict.known = expected != 0;
  verdict.hit = verdict.known && IsTopOneHit(update.ranking, expected);
  verdict.object = object;
  if (!update.ranking.empty()) {
    const ObjectId answer = update.ranking[0].object;
    verdict.answer = model_set.objects()[model_set.PositionOf(answer)].object->model().name;
  }
  verdict.decision = update.decision;
  verdict.unknown_statistic = update.unknown_statistic;
  verdict.unknown_p_value = update.unknown_p_value;
  verdict.confidence = update.confidence;
  if (update.noise_sigma) verdict.noise_sigma = *update.noise_sigma;
  if (update.blur) verdict.blur = *update.blur;
  if (verdict.hit && true_azimuth && update.pose) {
    verdict.pose_error = std::abs(AzimuthChange(*true_azimuth, update.pose->azimuth));
    verdict.pose_spread = update.pose->spread;
  }
}

// Adds one query's outcome to its cell.
void Count(const Outcome& outcome, EvaluationCell& cell) {
  if (outcome.answered) cell.Add(outcome.verdict, outcome.seconds);
}

// Whether `method` is evaluated on descriptors of `variant`, one of the run's variants. The
// product runs on its own variant and on every other variant with appearance channels the run
// lists, as a server runs it on a store made in one (`orbit serve --variant`).
bool Evaluates(std::string_view method, DescriptorVariant variant) {
  const std::optional<DescriptorVariant> own = OwnVariant(method);
  return !own || *own == variant || HasAppearanceChannels(variant);
}

// One engine per method and variant of the run (a method's options may depend on the variant:
// ResolveMethod), reused across tasks (ObserveSequence resets them): a task takes a set for its
// variant, made anew when none is idle, and gives it back. Thread-safe.
class EnginePool {
 public:
  using Engines = std::vector<std::unique_ptr<RecognitionEngine>>;

  explicit EnginePool(const EvaluationOptions& options, const EngineOptions& engine_options)
      : idle_(options.variants.size()) {
    for (DescriptorVariant variant : options.variants) {
      std::vector<Method>& methods = methods_.emplace_back();
      for (const std::string& name : options.methods) {
        methods.push_back(
            ResolveMethod(name, engine_options, variant, options.product_false_accept_rate));
      }
    }
  }

  // A set of engines for the run's variant at position `variant`.
  Engines Take(std::size_t variant) ABSL_LOCKS_EXCLUDED(mutex_) {
    {
      MutexLock lock(&mutex_);
      if (!idle_[variant].empty()) {
        Engines engines = std::move(idle_[variant].back());
        idle_[variant].pop_back();
        return engines;
      }
    }
    Engines engines;
    for (const Method& method : methods_[variant]) {
      engines.push_back(CreateEngine(method.engine, method.options));
    }
    return engines;
  }

  void Give(std::size_t variant, Engines engines) ABSL_LOCKS_EXCLUDED(mutex_) {
    MutexLock lock(&mutex_);
    idle_[variant].push_back(std::move(engines));
  }

 private:
  std::vector<std::vector<Method>> methods_;  // [variant][method]
  Mutex mutex_;
  std::vector<std::vector<Engines>> idle_ ABSL_GUARDED_BY(mutex_);  // [variant]
};

// The index a trial of known object `object` queries: every model, the object's own without
// the views near its query (query.removed_views), beside the distractors when there are any.
std::shared_ptr<const ViewIndexSnapshot> TrialIndex(const VariantModels& variant,
                                                    std::size_t object, const TrialQuery& query,
                                                    const ViewIndexOptions& options) {
  const std::vector<ObjectModel>& models = variant.models;
  std::vector<ObjectModel> trial_models;
  trial_models.reserve(models.size());
  for (std::size_t o = 0; o < models.size(); ++o) {
    if (o != object) {
      trial_models.push_back(models[o]);
      continue;
    }
    ObjectModel reduced = WithoutViews(models[o], query.removed_views);
    // A model left without views (tiny datasets only) cannot be indexed: the object is
    // absent from this trial's model set and the query cannot hit.
    if (!reduced.views.empty()) trial_models.push_back(std::move(reduced));
  }
  if (variant.distractors) return variant.distractors->With(std::move(trial_models));
  return ViewIndex(std::move(trial_models), options).Snapshot();
}

// One active query (EvaluationOptions::active_step) of one method: the protocol's first views
// (two, or one when n = 1), then NextActiveView after each update as `policy` says, each
// frame's device azimuth its true azimuth + the first frame's offset + N(0, 3 degrees) (the
// k-th frame's draw the same on every path). Returns the last update and sets `latest_view` to
// the view of the last frame.
struct ActiveQueryInput {
  const VariantModels* models = nullptr;  // the variant's known objects
  std::size_t object = 0;                 // the target's position
  bool known = true;
  ObjectId expected = 0;                                // the target's id; 0 for unknown
  std::shared_ptr<const ViewIndexSnapshot> full_index;  // for unknown targets
  std::vector<double> azimuths;                         // the target's views' true azimuths
  // A view's query frame under the distortion (descriptor and noise reading; no azimuth).
  std::function<QueryFrame(int view)> frame;
  std::uint64_t trial_seed = 0;
  int n = 1;
  double step = 20;
  ActivePolicy policy = ActivePolicy::kFollowMoves;
  bool use_orientation = true;
  ViewIndexOptions index;
};

// `frame` with the readings its device sends; none with options.use_quality_reading off.
QueryFrame WithReadings(QueryFrame frame, const FrameQuality& quality,
                        const EvaluationOptions& options) {
  if (options.use_quality_reading) {
    frame.noise_sigma = quality.noise_sigma;
    frame.blur = quality.blur;
  }
  return frame;
}

// How good `update` is for the truth, for ActivePolicy::kBestOfBoth: 2 a right top-1 accepted,
// 1 a right top-1, 0 otherwise; for an unknown target 1 when not accepted.
int ScoreForTruth(const FrameUpdate& update, ObjectId expected) {
  if (expected == 0) return update.decision == Decision::kAccept ? 0 : 1;
  if (!IsTopOneHit(update.ranking, expected)) return 0;
  return update.decision == Decision::kAccept ? 2 : 1;
}

class ActiveQuery {
 public:
  ActiveQuery(RecognitionEngine& engine, const ActiveQueryInput& in) : engine_(engine), in_(in) {
    SeededRandom noise(MixSeed(in.trial_seed, 0x616374697665ULL /* "active" */));
    for (int k = 0; k < in.n; ++k) noise_.push_back(kQueryAzimuthNoiseDegrees * noise.Normal());
  }

  FrameUpdate Run(int& latest_view) {
    const TrialQuery first = SampleTrial(in_.azimuths, std::min(in_.n, 2), in_.trial_seed);
    offset_ = first.azimuths[0] - in_.azimuths[first.views[0]];
    Path path{first.views, {}, 1};
    for (std::size_t k = 0; k < path.views.size(); ++k) {
      QueryFrame& frame = path.frames.emplace_back(in_.frame(path.views[k]));
      if (in_.use_orientation) frame.azimuth = first.azimuths[k];
    }
    return Extend(std::move(path), latest_view);
  }

 private:
  struct Path {
    std::vector<int> views;
    std::vector<QueryFrame> frames;
    int direction = 1;  // the way the last step went (NextActiveView)
  };

  FrameUpdate Extend(Path path, int& latest_view) {
    const std::shared_ptr<const ViewIndexSnapshot> index =
        in_.known ? TrialIndex(*in_.models, in_.object,
                               {path.views, {}, ExcludedViews(in_.azimuths, path.views)}, in_.index)
                  : in_.full_index;
    const FrameUpdate update = engine_.ObserveSequence(index, path.frames);
    if (static_cast<int>(path.frames.size()) == in_.n) {
      latest_view = path.views.back();
      return update;
    }
    switch (in_.policy) {
      case ActivePolicy::kFollowMoves:
        return Extend(Step(std::move(path), update.move), latest_view);
      case ActivePolicy::kOneWay:
        return Extend(Step(std::move(path), SuggestedMove::kNone), latest_view);
      case ActivePolicy::kBestOfBoth: break;
    }
    int right_view = 0;
    const FrameUpdate right = Extend(Step(path, SuggestedMove::kRight), right_view);
    int left_view = 0;
    const FrameUpdate left = Extend(Step(std::move(path), SuggestedMove::kLeft), left_view);
    const bool left_better = ScoreForTruth(left, in_.expected) > ScoreForTruth(right, in_.expected);
    latest_view = left_better ? left_view : right_view;
    return left_better ? left : right;
  }

  // `path` with its next view, `move`'s way from its latest.
  Path Step(Path path, SuggestedMove move) const {
    const int next =
        NextActiveView(in_.azimuths, path.views.back(), move, in_.step, path.direction);
    const double azimuth =
        NormaliseAzimuth(in_.azimuths[next] + offset_ + noise_[path.frames.size()]);
    path.views.push_back(next);
    QueryFrame& frame = path.frames.emplace_back(in_.frame(next));
    if (in_.use_orientation) frame.azimuth = azimuth;
    return path;
  }

  RecognitionEngine& engine_;
  const ActiveQueryInput& in_;
  std::vector<double> noise_;  // the k-th frame's azimuth noise
  double offset_ = 0;
};

// One method's answer to a task's query under one distortion, and the model azimuth its latest
// frame was taken at, when known (for the pose error).
struct Answer {
  FrameUpdate update;
  std::optional<double> latest_azimuth;
};

// What one task asks every method: its right answer and, per distortion, an engine's answer.
struct TaskQuery {
  bool skipped = false;   // the task asks nothing
  std::string object;     // the query's object, by name
  ObjectId expected = 0;  // 0: an object outside the model set, whose right answer is kUnknown
  std::function<Answer(RecognitionEngine& engine, std::size_t distortion)> ask;
};

// Step 3: every task of `grid` on `threads` threads, each method of `options` answering
// `query_of(task)` under every distortion; returns the outcome table.
std::vector<Outcome> RunTasks(const TrialGrid& grid, const EvaluationOptions& options,
                              const std::vector<VariantModels>& models,
                              const EngineOptions& engine_options, int threads,
                              const std::function<TaskQuery(const TrialGrid::Task&)>& query_of) {
  std::vector<Outcome> outcomes(grid.outcome_count());
  EnginePool pool(options, engine_options);
  RunStage(grid.task_count(), threads, "trials", options, [&](std::size_t task) {
    const TrialGrid::Task t = grid.TaskAt(task);
    const TaskQuery query = query_of(t);
    if (query.skipped) return;
    EnginePool::Engines engines = pool.Take(t.variant);
    for (std::size_t d = 0; d < grid.distortions; ++d) {
      for (std::size_t m = 0; m < grid.methods; ++m) {
        if (!Evaluates(options.methods[m], options.variants[t.variant])) continue;
        engines[m]->SetCalibration(models[t.variant].calibration);
        const Clock::time_point start = Clock::now();
        const Answer answer = query.ask(*engines[m], d);
        Outcome& outcome = outcomes[grid.OutcomeSlot(task, d, m)];
        outcome.seconds = SecondsSince(start);
        outcome.answered = true;
        Judge(answer.update, *models[t.variant].full_index, query.object, query.expected,
              answer.latest_azimuth, outcome);
      }
    }
    pool.Give(t.variant, std::move(engines));
  });
  return outcomes;
}

// The protocol's query of task `t` (docs/design.md#trials): n views of the object drawn with
// its own TrialSeed (SampleTrial), asked against every model, the object's own without the views
// near its query, or for an unknown object the full index; with --active, views taken where the
// method's moves point.
TaskQuery ProtocolQuery(const TrialGrid::Task& t, const EvaluationDataset& dataset,
                        const DescribedImages& described, const std::vector<VariantModels>& models,
                        const EvaluationOptions& options) {
  const int n = options.query_lengths[t.n_slot];
  const DatasetObject& target = dataset.object(t.object);
  std::vector<double> azimuths;
  for (std::size_t i : target.images) azimuths.push_back(dataset.images[i]->azimuth);
  const std::uint64_t trial_seed =
      TrialSeed(options.seed, static_cast<int>(t.object), n, static_cast<int>(t.trial));
  const TrialQuery trial = SampleTrial(azimuths, n, trial_seed);
  const bool is_known = dataset.is_known(t.object);
  const ObjectId object_id = static_cast<ObjectId>(t.object + 1);
  const std::shared_ptr<const ViewIndexSnapshot> snapshot =
      is_known ? TrialIndex(models[t.variant], t.object, trial, options.index)
               : models[t.variant].full_index;
  const DescriptorVariant variant = options.variants[t.variant];
  // The frame of view `view` (a position in the object's images) under distortion d.
  const auto frame = [&described, &options, images = &target.images, t, variant](
                         int view, std::size_t d, std::optional<double> azimuth) {
    const DescribedImage& image = described[(*images)[view]][t.variant];
    return WithReadings({{variant, image.queries[d]}, azimuth}, image.query_quality[d], options);
  };
  TaskQuery query;
  query.object = target.name;
  query.expected = is_known ? object_id : 0;
  query.ask = [=, &dataset, &models, &options, target_images = &target.images](
                  RecognitionEngine& engine, std::size_t d) {
    int latest_view = trial.views.back();
    Answer answer;
    if (options.active_step > 0) {
      ActiveQueryInput active{&models[t.variant],
                              t.object,
                              is_known,
                              is_known ? object_id : 0,
                              models[t.variant].full_index,
                              azimuths,
                              nullptr,
                              trial_seed,
                              n,
                              options.active_step,
                              options.active_policy,
                              options.use_orientation,
                              options.index};
      active.frame = [&frame, d](int view) { return frame(view, d, std::nullopt); };
      answer.update = ActiveQuery(engine, active).Run(latest_view);
    } else {
      std::vector<QueryFrame> frames;
      for (std::size_t k = 0; k < trial.views.size(); ++k) {
        frames.push_back(frame(
            trial.views[k], d,
            options.use_orientation ? std::optional<double>(trial.azimuths[k]) : std::nullopt));
      }
      answer.update = engine.ObserveSequence(snapshot, frames);
    }
    answer.latest_azimuth = dataset.images[(*target_images)[latest_view]]->azimuth;
    return answer;
  };
  return query;
}

// The report's cells, in its fixed order (variant, distortion, method, n), each summing its
// outcomes over every object and trial.
std::vector<EvaluationCell> AggregateCells(const std::vector<Outcome>& outcomes,
                                           const TrialGrid& grid,
                                           const EvaluationOptions& options) {
  std::vector<EvaluationCell> cells;
  for (std::size_t v = 0; v < grid.variants; ++v) {
    for (std::size_t d = 0; d < grid.distortions; ++d) {
      for (std::size_t m = 0; m < grid.methods; ++m) {
        if (!Evaluates(options.methods[m], options.variants[v])) continue;
        for (std::size_t s = 0; s < grid.ns; ++s) {
          EvaluationCell cell;
          cell.method = options.methods[m];
          cell.variant = options.variants[v];
          cell.distortion = options.distortions[d].name;
          cell.n = options.query_lengths[s];
          for (std::size_t object = 0; object < grid.objects; ++object) {
            for (std::size_t trial = 0; trial < grid.trials; ++trial) {
              const std::size_t task = grid.TaskNumber({v, object, s, trial});
              Count(outcomes[grid.OutcomeSlot(task, d, m)], cell);
            }
          }
          cells.push_back(std::move(cell));
        }
      }
    }
  }
  return cells;
}

}  // namespace

void EvaluationCell::Add(const QueryVerdict& verdict, double query_seconds) {
  seconds += query_seconds;
  if (verdict.known) {
    ++trials;
    hits += verdict.hit;
    accepted += verdict.hit && verdict.decision == Decision::kAccept;
    accepted_wrong += !verdict.hit && verdict.decision == Decision::kAccept;
  } else {
    ++unknown_trials;
    rejected += verdict.decision == Decision::kUnknown;
  }
  verdicts.push_back(verdict);
}

std::vector<std::string> DefaultMethods() {
  std::vector<std::string> methods{std::string(kProductMethod)};
  methods.insert(methods.end(), EngineNames().begin(), EngineNames().end());
  return methods;
}

std::uint64_t ImageNoiseSeed(std::uint64_t seed, std::size_t image) {
  return MixSeed(MixSeed(seed, 0x6e6f697365ULL /* "noise" */), image);
}

std::vector<DescribedImage> DescribeImage(const DatasetImage& image, std::size_t position,
                                          const std::vector<DescriptorVariant>& variants,
                                          const std::vector<DistortionSpec>& distortions,
                                          std::uint64_t seed) {
  // The region alone is distorted, as a device crops its tracker's box before describing it
  // (evaluation/dataset.h, ReadDescribedRegion).
  const cv::Mat view = ReadDescribedRegion(image);
  // The model view is described as every enrollment path describes it; its motion-blurred
  // copy is the MB query (motion blur draws nothing). Other queries are distorted here, the
  // image once for all variants.
  static const DistortionSpec protocol_blur = ParseDistortionSpec("mb");
  std::vector<cv::Mat> distorted(distortions.size());
  std::vector<FrameQuality> quality(distortions.size());
  for (std::size_t d = 0; d < distortions.size(); ++d) {
    distorted[d] = distortions[d].steps.empty()
                       ? view
                       : ApplyDistortion(view, distortions[d], ImageNoiseSeed(seed, position));
    quality[d] = MeasureFrameQuality(distorted[d]);
  }
  std::vector<DescribedImage> described;
  for (DescriptorVariant variant : variants) {
    const ViewDescription description = DescribeView(view, variant, seed);
    DescribedImage& d = described.emplace_back();
    d.view = {description.descriptor, image.azimuth, image.elevation, description.typical_distance};
    d.query_quality = quality;
    for (std::size_t q = 0; q < distortions.size(); ++q) {
      if (distortions[q].steps.empty()) {
        d.queries.push_back(description.descriptor);
      } else if (distortions[q] == protocol_blur) {
        d.queries.push_back(description.distorted[0]);  // the same image as distorted[q]
      } else {
        d.queries.push_back(ExtractCedd(distorted[q], variant).values);
      }
    }
  }
  return described;
}

namespace {

constexpr std::array<std::pair<ActivePolicy, std::string_view>, 3> kActivePolicyNames = {{
    {ActivePolicy::kFollowMoves, "follow"},
    {ActivePolicy::kOneWay, "one-way"},
    {ActivePolicy::kBestOfBoth, "oracle"},
}};

}  // namespace

std::string_view ActivePolicyName(ActivePolicy policy) {
  for (const auto& [p, name] : kActivePolicyNames) {
    if (p == policy) return name;
  }
  return "?";
}

std::optional<ActivePolicy> ParseActivePolicy(std::string_view name) {
  for (const auto& [policy, n] : kActivePolicyNames) {
    if (n == name) return policy;
  }
  return std::nullopt;
}

EvaluationReport RunEvaluation(const std::vector<DatasetImage>& known,
                               const std::vector<DatasetImage>& unknown,
                               const EvaluationOptions& requested) {
  const EvaluationOptions options = WithProductVariant(requested);
  const EvaluationDataset dataset = ValidateAndGroup(known, unknown, options);
  EvaluationReport report = ReportOf(options);
  report.known_objects = dataset.known.size();
  report.unknown_objects = dataset.unknown.size();
  report.distractors = static_cast<std::size_t>(options.distractors);
  if (options.distractors > 0 && options.distractor_models) {
    report.distractors_from = options.distractors_from;
  }
  report.images = dataset.images.size();

  const Clock::time_point descriptor_start = Clock::now();
  const DescribedImages described = DescribeImages(dataset, options, report.threads);
  report.descriptor_seconds = SecondsSince(descriptor_start);

  const std::vector<VariantModels> models =
      BuildModels(dataset, described, options, report.threads);
  for (const VariantModels& variant : models) report.memory.push_back(variant.memory);

  const TrialGrid grid{options.variants.size(),      dataset.object_count(),
                       options.query_lengths.size(), static_cast<std::size_t>(options.trials),
                       options.distortions.size(),   options.methods.size()};
  const Clock::time_point trial_start = Clock::now();
  const std::vector<Outcome> outcomes =
      RunTasks(grid, options, models, report.engine, report.threads, [&](const TrialGrid::Task& t) {
        return ProtocolQuery(t, dataset, described, models, options);
      });
  report.trial_seconds = SecondsSince(trial_start);

  report.cells = AggregateCells(outcomes, grid, options);
  return report;
}

EvaluationReport RunCaptureEvaluation(const std::vector<DatasetImage>& known,
                                      const std::vector<CaptureFrame>& captures,
                                      const EvaluationOptions& requested) {
  const EvaluationOptions options = WithProductVariant(requested);
  ValidateOptions(known, options);
  EvaluationDataset dataset;
  dataset.known = GroupByObject(known);
  for (const DatasetImage& image : known) dataset.images.push_back(&image);
  const std::vector<CaptureSequence> sequences = GroupCaptureSequences(captures);
  const std::vector<DatasetImage> frames =
      CaptureImages(captures, options.boxes, options.box_margin);

  EvaluationReport report = ReportOf(options);
  report.known_objects = dataset.known.size();
  std::set<std::string> unknown_objects;
  std::vector<ObjectId> expected(sequences.size(), 0);  // 0: not in the model set
  for (std::size_t s = 0; s < sequences.size(); ++s) {
    for (std::size_t o = 0; o < dataset.known.size(); ++o) {
      if (dataset.known[o].name == sequences[s].object) expected[s] = static_cast<ObjectId>(o + 1);
    }
    if (expected[s] == 0) unknown_objects.insert(sequences[s].object);
  }
  report.unknown_objects = unknown_objects.size();
  report.images = known.size() + captures.size();
  report.query_sequences = sequences.size();
  report.query_frames = captures.size();

  // Step 1: the model views, then every captured frame's query descriptors,
  // queries[frame][variant][distortion] (a frame is no model view: only its queries are made).
  const Clock::time_point descriptor_start = Clock::now();
  DescribedImages described(known.size());
  std::vector<std::vector<std::vector<DescriptorValues>>> queries(captures.size());
  std::vector<std::vector<FrameQuality>> quality(captures.size());  // [frame][distortion]
  RunStage(known.size() + captures.size(), report.threads, "descriptors", options,
           [&](std::size_t i) {
             if (i < known.size()) {
               described[i] = DescribeImage(known[i], i, options.variants, {}, options.seed);
               return;
             }
             // The region alone is distorted, as for the model set's images (DescribeImage).
             const std::size_t f = i - known.size();
             const cv::Mat whole = ReadCaptureImage(captures[f]);
             const cv::Mat image =
                 frames[f].box ? whole(DescribedRegion(frames[f], whole.size())) : whole;
             auto& frame = queries[f];
             frame.assign(options.variants.size(), {});
             for (const DistortionSpec& distortion : options.distortions) {
               const cv::Mat query =
                   distortion.steps.empty()
                       ? image
                       : ApplyDistortion(image, distortion, ImageNoiseSeed(options.seed, i));
               for (std::size_t v = 0; v < options.variants.size(); ++v) {
                 frame[v].push_back(ExtractCedd(query, options.variants[v]).values);
               }
               quality[f].push_back(MeasureFrameQuality(query));
             }
           });
  report.descriptor_seconds = SecondsSince(descriptor_start);
  const std::vector<VariantModels> models =
      BuildModels(dataset, described, options, report.threads);
  for (const VariantModels& variant : models) report.memory.push_back(variant.memory);

  // Step 3: one task per (variant, sequence, n): the sequence's first n frames, asked against
  // the full index; a sequence shorter than n asks nothing.
  const TrialGrid grid{options.variants.size(),      sequences.size(),
                       options.query_lengths.size(), 1,
                       options.distortions.size(),   options.methods.size()};
  const Clock::time_point trial_start = Clock::now();
  const std::vector<Outcome> outcomes =
      RunTasks(grid, options, models, report.engine, report.threads, [&](const TrialGrid::Task& t) {
        const CaptureSequence* sequence = &sequences[t.object];
        const int n = options.query_lengths[t.n_slot];
        TaskQuery query;
        query.skipped = static_cast<int>(sequence->frames.size()) < n;
        query.object = sequence->object;
        query.expected = expected[t.object];
        query.ask = [&, sequence, t, n](RecognitionEngine& engine, std::size_t d) {
          std::vector<QueryFrame> frames;
          for (int k = 0; k < n; ++k) {
            const std::size_t f = sequence->frames[static_cast<std::size_t>(k)];
            frames.push_back(
                WithReadings({{options.variants[t.variant], queries[f][t.variant][d]},
                              options.use_orientation ? captures[f].azimuth : std::nullopt},
                             quality[f][d], options));
          }
          return Answer{engine.ObserveSequence(models[t.variant].full_index, frames), {}};
        };
        return query;
      });
  report.trial_seconds = SecondsSince(trial_start);
  report.cells = AggregateCells(outcomes, grid, options);
  return report;
}

}  // namespace orbit
