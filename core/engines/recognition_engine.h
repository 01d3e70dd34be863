// RecognitionEngine: one recognition session's state and its frame-by-frame answer, the
// interface every engine implements (docs/design.md#engines). Engines are made by name
// (core/engines/engine_registry.h):
//
//   std::unique_ptr<RecognitionEngine> engine = CreateEngine("vci", options);
//   for each frame:  FrameUpdate u = engine->Observe(index.Snapshot(), {descriptor, azimuth});
//
// Every engine answers from a sliding window of the last options().window frames alone, so
// feeding frames one by one with Observe() and giving them all at once to ObserveSequence()
// yield the same final update.
//
// Scores: higher is better for every engine, and comparable across engines as a per-frame
// similarity (docs/design.md#windows-and-scores).
//
// Angles: only differences between frame azimuths are used; shifting every azimuth of a session
// by the same constant leaves every update unchanged, and sequences may cross 0/360.
//
// Index updates: each call takes the snapshot to answer from; when it differs from the previous
// call's, objects enrolled or deleted since are seen from this frame on, with work proportional
// to the change, not to the index, so that an enrollment does not stall every open session. The
// answer is the one a fresh session given the same window on the new snapshot would give (the
// HMM over candidates: up to the objects its frames proposed, core/engines/candidate_hmm.h).
//
// Thread safety: an engine (a session) must be used by one thread at a time; different engines
// may run concurrently on the same snapshot.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "core/decision/active_vision.h"
#include "core/decision/pose_estimate.h"
#include "core/decision/rejection.h"
#include "core/descriptor/query_frame.h"
#include "core/engines/engine_options.h"
#include "core/index/view_index.h"
#include "core/model/object_model.h"

namespace orbit {

class RejectionCalibration;

struct RankedObject {
  ObjectId object = 0;
  double score = 0;  // higher is better; see "Scores" above
};

// The answer to one frame.
struct FrameUpdate {
  std::int64_t frame_index = 0;       // 0 for the first frame after construction or Reset()
  std::vector<RankedObject> ranking;  // best first, at most options.top_k; empty index: empty
  Decision decision = Decision::kUndecided;
  SuggestedMove move = SuggestedMove::kNone;
  // The winner's unknown statistic U (docs/design.md#unknown-statistic; 0 for an empty index)
  // and the share of unknown objects' windows that look at least as known as this one once the
  // quality allowance is taken off U (the calibration's p-value; 1 without a calibration).
  double unknown_statistic = 0;
  double unknown_p_value = 1;
  // The mean noise and blur readings of the window's frames that carry one (MeanReading,
  // core/decision/quality_allowance.h); none when no frame does or the index is empty.
  std::optional<double> noise_sigma;
  std::optional<double> blur;
  // How likely the top-1 object is the one in front of the camera, in [0, 1]
  // (docs/design.md#confidence); 0 for an empty index.
  double confidence = 0;
  std::optional<PoseEstimate> pose;  // the winner's; none for an empty index
};

class RecognitionEngine {
 public:
  virtual ~RecognitionEngine();

  RecognitionEngine(const RecognitionEngine&) = delete;
  RecognitionEngine& operator=(const RecognitionEngine&) = delete;

  // Adds one frame to the window (dropping the oldest when it holds options().window frames)
  // and returns the answer for the window.
  // Throws std::invalid_argument when `index` is null, when the frame's variant is not the
  // index's, or when a frame value is out of its range (ValidateQueryFrame); the session's state
  // is then unchanged.
  virtual FrameUpdate Observe(std::shared_ptr<const ViewIndexSnapshot> index,
                              const QueryFrame& frame) = 0;

  // Batch form: Reset(), then all frames in order, answering once. Equal to the last update of
  // Observe() called on each frame after a Reset(). Throws as Observe() (and
  // std::invalid_argument for an empty `frames`), leaving the session reset.
  virtual FrameUpdate ObserveSequence(std::shared_ptr<const ViewIndexSnapshot> index,
                                      std::span<const QueryFrame> frames) = 0;

  // Forgets every frame; the next frame has index 0.
  virtual void Reset() = 0;

  // The calibration the kCalibrated rule takes its threshold from, from the next frame on
  // (typically the model set's, recomputed as it changes; null: none). Ignored by the
  // kTypicalDistance rule.
  virtual void SetCalibration(std::shared_ptr<const RejectionCalibration> calibration) = 0;

  // One of EngineNames() (core/engines/engine_registry.h).
  std::string_view name() const { return name_; }
  const EngineOptions& options() const { return options_; }

 protected:
  // Throws std::invalid_argument when `options` are out of range (ValidateEngineOptions).
  RecognitionEngine(std::string_view name, const EngineOptions& options);

 private:
  const std::string_view name_;
  const EngineOptions options_;
};

}  // namespace orbit
