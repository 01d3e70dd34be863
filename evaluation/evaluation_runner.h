// EvaluationRunner: runs the evaluation protocol (evaluation/evaluation_protocol.h,
// docs/design.md#evaluation-protocol) on a dataset of images and counts hits per method x
// descriptor variant x distortion x query length n. The engine of `orbit eval`.
//
// What it does, in order:
//   1. reads every image once and, for each variant, on all threads, describes it as a model
//      view exactly as every enrollment path does (DescribeImage:
//      core/descriptor/view_description.h, DescribeView with `seed` as the base of the seed rule:
//      CEDD, motion-blurred copy, typical distance), and computes its query under each distortion
//      (evaluation/distortion_spec.h), whose noise is drawn with ImageNoiseSeed(seed, i), so reruns
//      see the same noise. The DF query is the view's CEDD, the MB query its motion-blurred copy;
//   2. builds each known object's model from its images' model views of step 1, and the index
//      of all known objects, whose memory the report gives;
//   3. runs the trials, one task per (variant, object, n, trial), spread over the threads: each
//      task draws its query (SampleTrial), builds a ViewIndex of all known objects with the
//      query object's excluded views removed, and asks every method, for every distortion, for
//      its answer to the whole query (RecognitionEngine::ObserveSequence). Unknown objects (not
//      in any model) are queried against the full index: the right answer is Decision::kUnknown.
// The counts are exact and the same for any thread count (each task's draws come from its own
// seed, evaluation/evaluation_protocol.h); times are wall-clock and vary from run to run.
//
// Thread safety: RunEvaluation may be called from any thread; it starts and joins its own.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "client/frame_quality.h"
#include "client/object_region.h"
#include "core/base/parallel_for.h"
#include "core/descriptor/descriptor.h"
#include "core/engines/engine_registry.h"
#include "core/engines/product_pipeline.h"
#include "core/engines/recognition_engine.h"
#include "core/index/view_index.h"
#include "core/model/object_model.h"
#include "evaluation/dataset.h"
#include "evaluation/distortion_spec.h"
#include "evaluation/evaluation_protocol.h"

namespace orbit {

// kProductMethod, then every engine of EngineNames().
std::vector<std::string> DefaultMethods();

// Which way an active query's next view goes (`orbit eval --active`, EvaluationOptions::
// active_step).
enum class ActivePolicy {
  kFollowMoves,  // "follow": the way the method's latest update suggested (on the same way at NONE)
  kOneWay,       // "one-way": always the same way, whatever the updates say: the control that
                 // measures the suggestion alone
  kBestOfBoth,   // "oracle": both ways at every step, keeping the path whose last answer is best
                 // for the truth (a right top-1 accepted, then a right top-1; for an unknown
                 // object, not accepted): the bound of any LEFT / RIGHT suggestion at this step.
                 // 2^(n-2) paths per query
};

// The policy's name, as above; and back (nullopt for any other text).
std::string_view ActivePolicyName(ActivePolicy policy);
std::optional<ActivePolicy> ParseActivePolicy(std::string_view name);

struct EvaluationOptions {
  std::vector<DescriptorVariant> variants{DescriptorVariant::kCeddLire};
  // Engine names (EngineNames()) and kProductMethod, the product pipeline (core/
  // product_pipeline.h: its engine with its options, whatever `engine` says, on its own variant,
  // which is evaluated, added last, when `variants` lacks it, and on every other variant with
  // appearance channels `variants` lists). By default the product and every engine.
  std::vector<std::string> methods = DefaultMethods();
  // Query distortions (evaluation/distortion_spec.h); by default the protocol's df, mb and gn.
  std::vector<DistortionSpec> distortions{ParseDistortionSpec("df"), ParseDistortionSpec("mb"),
                                          ParseDistortionSpec("gn")};
  std::vector<int> query_lengths{1, 2, 4, 6, 8};  // n: frames per query (1..kMaxWindow)
  int trials = 10;                                // trials per object and n (>= 1)
  // false: the query frames carry no azimuth, as from a device without an orientation sensor
  // (QueryFrame); every method then runs on the descriptors alone (`--orientation ignore`).
  bool use_orientation = true;
  // false: the query frames carry no quality readings (noise, blur), as from a device that
  // does not measure them (`--quality-reading ignore`); the calibrated rule then makes no
  // allowance for degraded frames (core/decision/quality_allowance.h).
  bool use_quality_reading = true;
  // RunCaptureEvaluation: the object's box in each captured frame (ReadBoxes' keys, matched as
  // AttachBoxes matches paths; every frame needs one): each frame is described in its box grown
  // by box_margin, as a model view with a box is. Empty: the whole frames.
  std::map<std::string, ImageBox> boxes;
  double box_margin = kDefaultBoxMargin;
  std::uint64_t seed = 1;  // every random draw derives from it
  // Active vision (`orbit eval --active`, docs/design.md#other-query-modes): 0 for the protocol's
  // random views; else each query takes the protocol's first two views, then each next view this
  // many degrees from its latest in the direction the method's latest update suggested
  // (NextActiveView, evaluation/evaluation_protocol.h), in capture order. Known objects' models
  // lack the views near every view taken so far, at each step.
  double active_step = 0;
  // With active_step: which way each step goes (ActivePolicy).
  ActivePolicy active_policy = ActivePolicy::kFollowMoves;
  ViewIndexOptions index;  // search mode (exact or kd-tree) and FLANN's parameters
  // Other objects added to every model set, never queried: recognition among this many other
  // objects (0..kMaxDistractors). Generated (evaluation/distractor_objects.h) unless
  // `distractor_models` is set.
  int distractors = 0;
  // Empty, or where the distractors come from instead (docs/design.md#distractors): called once
  // per evaluated variant with `distractors` and that variant, it returns that many models of the
  // variant (their ids are replaced), or throws to refuse the evaluation. `distractors_from`
  // names that source in the report.
  std::function<std::vector<ObjectModel>(int count, DescriptorVariant variant)> distractor_models;
  std::string distractors_from;
  EngineOptions engine;  // the engines' options; the window is raised to the largest n
  // The product's target false-accept rate; unset: on each variant, the variant's own
  // (ProductFalseAcceptRate), as a server takes it. The engines' is engine.false_accept_rate.
  std::optional<double> product_false_accept_rate;
  int threads = 0;  // worker threads; 0: every CPU this process may run on
  // Called from the worker threads (never concurrently) as work completes: the stage
  // ("descriptors" or "trials"), tasks done and tasks in the stage. May be empty.
  std::function<void(std::string_view stage, std::size_t done, std::size_t total)> progress;
};

// One method's answer to one query, as the recognition reports need it.
struct QueryVerdict {
  bool known = false;  // the query's object is in the model set
  bool hit = false;    // known, and the top-1 object is right
  std::string object;  // the query's object, by name
  std::string answer;  // the top-1 object, by name; "" for an empty ranking
  Decision decision = Decision::kUndecided;
  // FrameUpdate's; NaN when the answer did not say (a server's update carries neither).
  double unknown_statistic = 0;
  double unknown_p_value = 1;
  double confidence = 0;
  // Known hits of the protocol only: |true azimuth of the latest frame - estimated pose|
  // (degrees, 0..180) and the estimate's spread; NaN otherwise.
  double pose_error = std::numeric_limits<double>::quiet_NaN();
  double pose_spread = std::numeric_limits<double>::quiet_NaN();
  double noise_sigma = std::numeric_limits<double>::quiet_NaN();  // FrameUpdate's; NaN: none
  double blur = std::numeric_limits<double>::quiet_NaN();         // FrameUpdate's; NaN: none
};

// Counts for one method, variant, distortion and n.
struct EvaluationCell {
  std::string method;
  DescriptorVariant variant = DescriptorVariant::kCeddLire;
  std::string distortion = "df";  // the DistortionSpec's name
  int n = 0;
  int trials = 0;          // queries of known objects
  int hits = 0;            // ... whose top-1 object was right
  int accepted = 0;        // ... whose top-1 object was right and was accepted (kAccept)
  int accepted_wrong = 0;  // ... whose top-1 object was wrong and was accepted
  int unknown_trials = 0;  // queries of unknown objects
  int rejected = 0;        // ... answered kUnknown
  // Time spent answering all queries counted here: wall-clock time in ObserveSequence, or for
  // a server's answers the processing time its updates state.
  double seconds = 0;
  std::vector<QueryVerdict> verdicts;  // every query counted here, known and unknown

  // Counts one more query: its verdict, answered in `query_seconds`.
  void Add(const QueryVerdict& verdict, double query_seconds);

  double hit_rate() const { return trials > 0 ? double(hits) / trials : 0; }
  double accept_rate() const { return trials > 0 ? double(accepted) / trials : 0; }
  double reject_rate() const { return unknown_trials > 0 ? double(rejected) / unknown_trials : 0; }
  // Mean time of one query (all n frames), milliseconds.
  double ms_per_query() const {
    const int queries = trials + unknown_trials;
    return queries > 0 ? 1000 * seconds / queries : 0;
  }
};

// The size of the full model set of one variant.
struct ModelMemory {
  DescriptorVariant variant = DescriptorVariant::kCeddLire;
  std::size_t objects = 0;
  std::size_t views = 0;
  std::size_t descriptor_bytes = 0;  // views x 144: the descriptors alone
  // Heap memory held by the ViewIndex of all known objects right after it was built, measured
  // by the allocator's statistics (glibc mallinfo2): descriptors, azimuths, typical distances,
  // the index's tables and, in kd-tree mode, FLANN's trees. Caches the engines fill later (e.g.
  // sector views) are not included.
  std::size_t index_bytes = 0;
};

// The running server whose answers a report counts (RunServerEvaluation,
// evaluation/server_evaluation.h), as its ServerInfo describes it.
struct ServerDescription {
  std::string address;  // HOST:PORT, as given
  std::string version;
  std::size_t views = 0;  // of its enrolled objects (their count is the report's known_objects)
  // Its session defaults, which every query ran with, in words: "engine hmm, window 8, ...".
  std::string defaults;
  // Whether those defaults are the product pipeline's (core/engines/product_pipeline.h), as far
  // as ServerInfo shows them.
  bool runs_product = false;
};

struct EvaluationReport {
  // Set when the answers came from a running server (RunServerEvaluation): then the model set
  // is the server's, `memory` is empty, and seed, index, threads and engine options are not
  // this process's.
  std::optional<ServerDescription> server;
  // One cell per variant x distortion x method x n, in that nesting order (the options' orders).
  std::vector<EvaluationCell> cells;
  std::vector<ModelMemory> memory;  // one per variant
  std::size_t known_objects = 0;
  std::size_t unknown_objects = 0;
  std::size_t distractors = 0;   // EvaluationOptions::distractors
  std::string distractors_from;  // EvaluationOptions::distractors_from; "" for generated ones
  std::size_t images = 0;
  // RunCaptureEvaluation: the captured query sequences and their frames (0 for the protocol).
  std::size_t query_sequences = 0;
  std::size_t query_frames = 0;
  std::uint64_t seed = 0;
  int threads = 0;  // worker threads used
  SearchMode search = SearchMode::kExact;
  bool use_orientation = true;                              // as the options said
  double active_step = 0;                                   // as the options said
  ActivePolicy active_policy = ActivePolicy::kFollowMoves;  // as the options said
  ViewIndexOptions index;                                   // as used
  EngineOptions engine;           // as used (window raised to the largest n)
  double descriptor_seconds = 0;  // wall-clock time of step 1
  double trial_seconds = 0;       // wall-clock time of step 3
};

// The seed of the noise of image i's queries (ApplyDistortion's seed).
std::uint64_t ImageNoiseSeed(std::uint64_t seed, std::size_t image);

// One image as the evaluation uses it, in one descriptor variant (step 1).
struct DescribedImage {
  // The model view it contributes: described exactly as every enrollment path describes it
  // (DescribeView with the options' seed as base), at the image's azimuth and elevation.
  ModelView view;
  // The query descriptor under each of the options' distortions, in their order: the CEDD of
  // ApplyDistortion(image, spec, ImageNoiseSeed(seed, position)). df's is the view's own CEDD,
  // mb's DescribeView's motion-blurred copy (the same image, not computed twice).
  std::vector<DescriptorValues> queries;
  // What the client library measures of each query image and sends as Frame.quality
  // (MeasureFrameQuality, client/frame_quality.h), in the same order.
  std::vector<FrameQuality> query_quality;
};

// Step 1 for one image: reads it once and describes it in each of `variants` (the results in
// that order), with its query under each of `distortions`. `position` is its place among the
// evaluated images (known ones first, then unknown ones), which seeds the noise of its queries:
// ImageNoiseSeed(seed, position). An image with a box is described in its object's region
// alone (ReadDescribedRegion, evaluation/dataset.h).
// Throws std::runtime_error naming the file when it cannot be read, std::invalid_argument
// naming the box's origin when the box is not inside the image (ObjectRegion).
std::vector<DescribedImage> DescribeImage(const DatasetImage& image, std::size_t position,
                                          const std::vector<DescriptorVariant>& variants,
                                          const std::vector<DistortionSpec>& distortions,
                                          std::uint64_t seed);

// Runs the protocol. `known` holds the images of the objects in the model set, `unknown` those
// of objects left out of it (may be empty); an object is the set of images sharing a name, and
// objects are numbered in order of first appearance.
//
// Throws std::invalid_argument for options out of range (no variant, method, distortion or n;
// an unknown method; n outside 1..kMaxWindow; trials < 1; threads < 0; engine or index options
// out of range), when `known` is empty, when an object appears in both lists, or when an object
// has fewer views than the largest n; std::runtime_error naming the file when an image cannot be
// read.
EvaluationReport RunEvaluation(const std::vector<DatasetImage>& known,
                               const std::vector<DatasetImage>& unknown,
                               const EvaluationOptions& options);

// Recognises captured query sequences (`orbit eval --queries`: a user's own camera frames,
// evaluation/dataset.h ReadQueryCaptures) against the model set of `known`, every image of
// which is a model view (nothing is left out: the captures are other images). A sequence is one
// query; for each n of the options it is asked with its first n frames (sequences shorter than
// n are not counted at that n), each frame under each of the options' distortions (df: as
// captured), with the frame's azimuth when it has one and options.use_orientation. A sequence
// of an object that is not in the model set counts as an unknown query (right when rejected).
// `trials` is not used. Cells as RunEvaluation's.
//
// Throws std::invalid_argument as RunEvaluation does for the options and `known`, and when a
// sequence shows more than one object; std::runtime_error naming an image that cannot be read,
// after the frame's origin ("FILE:LINE: ") when it has one.
EvaluationReport RunCaptureEvaluation(const std::vector<DatasetImage>& known,
                                      const std::vector<CaptureFrame>& captures,
                                      const EvaluationOptions& options);

}  // namespace orbit
