#include "evaluation/evaluation_runner.h"

#include <malloc.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "client/image_file.h"
#include "core/cedd.h"
#include "core/seeded_random.h"
#include "core/parallel_for.h"
#include "core/view_description.h"

namespace orbit {
namespace {

// Every image has a query descriptor under each distortion (DF, MB, GN).
constexpr std::size_t kDistortionCount = kQueryDistortions.size();

std::size_t DistortionSlot(QueryDistortion d) {
  return static_cast<std::size_t>(std::find(kQueryDistortions.begin(), kQueryDistortions.end(), d) -
                                  kQueryDistortions.begin());
}

// Images grouped by object name, objects in order of first appearance.
struct DatasetObject {
  std::string name;
  std::vector<std::size_t> images;  // positions in the combined image list
};

std::vector<DatasetObject> GroupByObject(const std::vector<DatasetImage>& images,
                                         std::size_t first_image) {
  std::vector<DatasetObject> objects;
  std::map<std::string, std::size_t> position;
  for (std::size_t i = 0; i < images.size(); ++i) {
    const auto [it, added] = position.emplace(images[i].object, objects.size());
    if (added) objects.push_back({images[i].object, {}});
    objects[it->second].images.push_back(first_image + i);
  }
  return objects;
}

// Bytes the allocator has handed out and not taken back (glibc's mallinfo2: arena and mmapped
// blocks). Its growth across a single-threaded step is the heap memory that step kept.
std::size_t HeapBytesInUse() {
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

void Validate(const std::vector<DatasetImage>& known, const EvaluationOptions& options) {
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
    require(std::find(names.begin(), names.end(), method) != names.end(),
            "unknown method \"" + method + "\"");
  }
  for (int n : options.query_lengths) {
    require(n >= 1 && n <= kMaxWindow,
            "n = " + std::to_string(n) + " is outside 1.." + std::to_string(kMaxWindow));
  }
  require(options.trials >= 1, "trials must be at least 1");
  require(options.threads >= 0, "threads must be >= 0");
  ValidateEngineOptions(options.engine);
  ViewIndex probe(options.variants.front(), options.index);  // validates the index options
}

// Descriptors of every image: [variant][distortion slot][image].
using DescriptorTable = std::vector<std::array<std::vector<DescriptorValues>, kDistortionCount>>;
// Typical distances of every image as a model view: [variant][image].
using TypicalDistanceTable = std::vector<std::vector<double>>;

}  // namespace

std::uint64_t ImageNoiseSeed(std::uint64_t seed, std::size_t image) {
  return MixSeed(MixSeed(seed, 0x6e6f697365ULL /* "noise" */), image);
}

EvaluationReport RunEvaluation(const std::vector<DatasetImage>& known,
                               const std::vector<DatasetImage>& unknown,
                               const EvaluationOptions& options) {
  Validate(known, options);
  using Clock = std::chrono::steady_clock;
  const auto seconds_since = [](Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
  };

  const std::vector<DatasetObject> known_objects = GroupByObject(known, 0);
  const std::vector<DatasetObject> unknown_objects = GroupByObject(unknown, known.size());
  const int max_n = *std::max_element(options.query_lengths.begin(), options.query_lengths.end());
  for (const auto& group : {&known_objects, &unknown_objects}) {
    for (const DatasetObject& object : *group) {
      if (static_cast<int>(object.images.size()) < max_n) {
        throw std::invalid_argument("object \"" + object.name + "\" has " +
                                    std::to_string(object.images.size()) +
                                    " views; n = " + std::to_string(max_n) + " needs as many");
      }
    }
  }
  for (const DatasetObject& object : unknown_objects) {
    if (std::any_of(known_objects.begin(), known_objects.end(),
                    [&](const DatasetObject& k) { return k.name == object.name; })) {
      throw std::invalid_argument("object \"" + object.name + "\" is both known and unknown");
    }
  }
  std::vector<const DatasetImage*> images;
  for (const DatasetImage& image : known) images.push_back(&image);
  for (const DatasetImage& image : unknown) images.push_back(&image);

  EvaluationReport report;
  report.known_objects = known_objects.size();
  report.unknown_objects = unknown_objects.size();
  report.images = images.size();
  report.seed = options.seed;
  report.search = options.index.search;
  report.threads = options.threads > 0 ? options.threads : AvailableCpus();
  const std::size_t variant_count = options.variants.size();

  // 1. Descriptors of every image under every distortion, for every variant.
  const Clock::time_point descriptor_start = Clock::now();
  DescriptorTable descriptors(variant_count);
  for (auto& per_variant : descriptors) {
    for (auto& per_distortion : per_variant) per_distortion.resize(images.size());
  }
  TypicalDistanceTable typical(variant_count, std::vector<double>(images.size()));
  RunStage(images.size(), report.threads, "descriptors", options, [&](std::size_t i) {
    const cv::Mat view = ReadImageFile(images[i]->path);
    // The GN query draws its own noise; the model view is described as every enrollment path
    // describes it (its MB copy is the MB query: motion blur draws nothing).
    const cv::Mat noisy = ApplyQueryDistortion(view, QueryDistortion::kGaussianNoise,
                                               ImageNoiseSeed(options.seed, i));
    for (std::size_t v = 0; v < variant_count; ++v) {
      const ViewDescription described = DescribeView(view, options.variants[v], options.seed);
      descriptors[v][DistortionSlot(QueryDistortion::kNone)][i] = described.descriptor;
      descriptors[v][DistortionSlot(QueryDistortion::kMotionBlur)][i] = described.distorted[0];
      descriptors[v][DistortionSlot(QueryDistortion::kGaussianNoise)][i] =
          ExtractCedd(noisy, options.variants[v]).values;
      typical[v][i] = described.typical_distance;
    }
  });
  report.descriptor_seconds = seconds_since(descriptor_start);

  // 2. Models of the known objects; ids are positions + 1.
  std::vector<std::vector<ObjectModel>> models(variant_count);
  for (std::size_t v = 0; v < variant_count; ++v) {
    const auto& table = descriptors[v];
    for (std::size_t o = 0; o < known_objects.size(); ++o) {
      ObjectModel model;
      model.id = static_cast<ObjectId>(o + 1);
      model.name = known_objects[o].name;
      model.variant = options.variants[v];
      for (std::size_t i : known_objects[o].images) {
        model.views.push_back({table[DistortionSlot(QueryDistortion::kNone)][i],
                               images[i]->azimuth, images[i]->elevation, typical[v][i]});
      }
      models[v].push_back(std::move(model));
    }
  }

  // The full index of each variant: the model memory, and the index unknown objects are
  // queried against (snapshots are immutable and shared by all threads).
  std::vector<std::shared_ptr<const ViewIndexSnapshot>> full_index(variant_count);
  for (std::size_t v = 0; v < variant_count; ++v) {
    ModelMemory memory;
    memory.variant = options.variants[v];
    memory.objects = models[v].size();
    for (const ObjectModel& model : models[v]) memory.views += model.views.size();
    memory.descriptor_bytes = memory.views * kDescriptorSize;
    const std::size_t before = HeapBytesInUse();
    const ViewIndex index(models[v], options.index);
    full_index[v] = index.Snapshot();
    const std::size_t after = HeapBytesInUse();
    memory.index_bytes = after > before ? after - before : 0;
    report.memory.push_back(memory);
  }

  // 3. Trials: tasks (variant, object, n, trial), known objects first, then unknown ones.
  const std::size_t n_count = options.query_lengths.size();
  const std::size_t trials = static_cast<std::size_t>(options.trials);
  const std::size_t object_count = known_objects.size() + unknown_objects.size();
  const std::size_t task_count = variant_count * object_count * n_count * trials;
  const std::size_t method_count = options.methods.size();
  const std::size_t distortion_count = options.distortions.size();

  struct Outcome {  // one method's answer to one query
    bool hit = false;
    bool accepted = false;
    bool rejected = false;
    double seconds = 0;
  };
  // [task][distortion][method], flattened.
  std::vector<Outcome> outcomes(task_count * distortion_count * method_count);

  EngineOptions engine_options = options.engine;
  engine_options.window = std::max(engine_options.window, max_n);
  report.engine = engine_options;
  report.index = options.index;

  const Clock::time_point trial_start = Clock::now();
  // One set of engines per thread, reused across tasks (ObserveSequence resets them).
  std::mutex engines_mutex;
  std::vector<std::vector<std::unique_ptr<RecognitionEngine>>> idle_engines;
  RunStage(task_count, report.threads, "trials", options, [&](std::size_t task) {
    std::vector<std::unique_ptr<RecognitionEngine>> engines;
    {
      std::lock_guard<std::mutex> lock(engines_mutex);
      if (!idle_engines.empty()) {
        engines = std::move(idle_engines.back());
        idle_engines.pop_back();
      }
    }
    if (engines.empty()) {
      for (const std::string& method : options.methods) {
        engines.push_back(CreateEngine(method, engine_options));
      }
    }

    const std::size_t trial = task % trials;
    const std::size_t n_slot = (task / trials) % n_count;
    const std::size_t object = (task / trials / n_count) % object_count;
    const std::size_t v = task / trials / n_count / object_count;
    const int n = options.query_lengths[n_slot];
    const bool is_known = object < known_objects.size();
    const DatasetObject& target =
        is_known ? known_objects[object] : unknown_objects[object - known_objects.size()];

    std::vector<double> azimuths;
    for (std::size_t i : target.images) azimuths.push_back(images[i]->azimuth);
    const TrialQuery query =
        SampleTrial(azimuths, n, TrialSeed(options.seed, static_cast<int>(object), n,
                                           static_cast<int>(trial)));

    std::shared_ptr<const ViewIndexSnapshot> snapshot = full_index[v];
    if (is_known) {
      std::vector<ObjectModel> trial_models;
      trial_models.reserve(models[v].size());
      for (std::size_t o = 0; o < models[v].size(); ++o) {
        if (o != object) {
          trial_models.push_back(models[v][o]);
          continue;
        }
        ObjectModel reduced = WithoutViews(models[v][o], query.removed_views);
        // A model left without views (tiny datasets only) cannot be indexed: the object is
        // absent from this trial's model set and the query cannot hit.
        if (!reduced.views.empty()) trial_models.push_back(std::move(reduced));
      }
      snapshot = ViewIndex(std::move(trial_models), options.index).Snapshot();
    }

    const ObjectId expected = static_cast<ObjectId>(object + 1);
    std::vector<QueryFrame> frames(query.views.size());
    for (std::size_t d = 0; d < distortion_count; ++d) {
      const auto& table = descriptors[v][DistortionSlot(options.distortions[d])];
      for (std::size_t k = 0; k < frames.size(); ++k) {
        frames[k].descriptor = {options.variants[v], table[target.images[query.views[k]]]};
        frames[k].azimuth = query.azimuths[k];
      }
      for (std::size_t m = 0; m < method_count; ++m) {
        const Clock::time_point start = Clock::now();
        const FrameUpdate update = engines[m]->ObserveSequence(snapshot, frames);
        Outcome& outcome = outcomes[(task * distortion_count + d) * method_count + m];
        outcome.seconds = seconds_since(start);
        if (is_known) {
          outcome.hit = IsTopOneHit(update.ranking, expected);
          outcome.accepted = outcome.hit && update.decision == Decision::kAccept;
        } else {
          outcome.rejected = update.decision == Decision::kUnknown;
        }
      }
    }
    std::lock_guard<std::mutex> lock(engines_mutex);
    idle_engines.push_back(std::move(engines));
  });
  report.trial_seconds = seconds_since(trial_start);

  // Aggregate in a fixed order: variant, distortion, method, n.
  for (std::size_t v = 0; v < variant_count; ++v) {
    for (std::size_t d = 0; d < distortion_count; ++d) {
      for (std::size_t m = 0; m < method_count; ++m) {
        for (std::size_t s = 0; s < n_count; ++s) {
          EvaluationCell cell;
          cell.method = options.methods[m];
          cell.variant = options.variants[v];
          cell.distortion = options.distortions[d];
          cell.n = options.query_lengths[s];
          for (std::size_t object = 0; object < object_count; ++object) {
            const bool is_known = object < known_objects.size();
            for (std::size_t trial = 0; trial < trials; ++trial) {
              const std::size_t task = ((v * object_count + object) * n_count + s) * trials + trial;
              const Outcome& outcome = outcomes[(task * distortion_count + d) * method_count + m];
              cell.seconds += outcome.seconds;
              if (is_known) {
                ++cell.trials;
                cell.hits += outcome.hit;
                cell.accepted += outcome.accepted;
              } else {
                ++cell.unknown_trials;
                cell.rejected += outcome.rejected;
              }
            }
          }
          report.cells.push_back(std::move(cell));
        }
      }
    }
  }
  return report;
}

}  // namespace orbit
