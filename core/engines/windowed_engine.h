// WindowedEngine: the sliding window every engine of the thesis runs on, and the answer built
// from an engine's assessments of the window (docs/design.md#windows-and-scores): rank, blend
// with the nearest views, judge the winner (accept or unknown, confidence, pose), suggest a move.
// An engine implements the per-frame work and Assess(); the rest is here, once.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "core/engines/recognition_engine.h"

namespace orbit {

class SimilarityRows;
struct ObjectRows;

class WindowedEngine : public RecognitionEngine {
 public:
  ~WindowedEngine() override;

  FrameUpdate Observe(std::shared_ptr<const ViewIndexSnapshot> index,
                      const QueryFrame& frame) final;
  FrameUpdate ObserveSequence(std::shared_ptr<const ViewIndexSnapshot> index,
                              std::span<const QueryFrame> frames) final;
  void Reset() final;
  void SetCalibration(std::shared_ptr<const RejectionCalibration> calibration) final;

 protected:
  WindowedEngine(std::string_view name, const EngineOptions& options);

  // One view matched to one window frame, for the threshold rule.
  struct MatchedView {
    int frame = 0;  // position in the window
    int view = 0;   // index in the object's ObjectModel::views
    double similarity = 0;
  };

  // An engine's verdict on one object for the current window.
  struct Assessment {
    const IndexedObject* object = nullptr;
    double score = 0;                  // higher is better
    std::vector<MatchedView> matched;  // the views the score used, one per frame
    // The object's azimuth facing the camera at the latest frame, in model degrees (for
    // active vision).
    double latest_azimuth = 0;
  };

  // A frame entered the window at its end (position window.size() - 1); do its per-frame work.
  virtual void Append(const ViewIndexSnapshot& index, const QueryFrame& frame) = 0;
  // The frame at window position 0 left.
  virtual void DropOldest() = 0;
  // Forget every per-frame state (Reset).
  virtual void Clear() = 0;
  // The model set changed from `before` to `after` by `change` while the frames of `window`
  // (oldest first, not empty) were in the window: bring their per-frame state to `after`.
  // Default: Clear(), then Append() each frame again on `after` (work proportional to the index).
  virtual void Rebase(const ViewIndexSnapshot& before, const ViewIndexSnapshot& after,
                      const SnapshotChange& change, std::span<const QueryFrame> window);
  // Every candidate object's assessment for the window, any order; `matched` and
  // `latest_azimuth` may be left for Complete(). `window` is not empty.
  virtual std::vector<Assessment> Assess(const ViewIndexSnapshot& index,
                                         std::span<const QueryFrame> window) = 0;
  // Fills `matched` and `latest_azimuth` of an assessment from the last Assess() call; called
  // only for the few objects the decision and the move need, with the object's similarity rows
  // for the window (rows.rows[t][v] = TC(window[t], view v), computed once per frame and
  // object). Default: Assess() filled them.
  virtual void Complete(const ViewIndexSnapshot& index, std::span<const QueryFrame> window,
                        const ObjectRows& rows, Assessment& assessment);

 private:
  void Validate(const ViewIndexSnapshot* index, const QueryFrame& frame) const;
  void Push(const QueryFrame& frame);

  // The answer for the window, in the steps below.
  FrameUpdate Answer();
  // Orders the best assessments (at least two, for the runner-up) and re-scores them with the
  // nearest-view blend; returns how many are ordered.
  std::size_t Rank(std::vector<Assessment>& assessments);
  // The winner's unknown statistic, confidence, readings and decision.
  void Judge(Assessment& winner, const Assessment* runner_up, FrameUpdate& update);
  // The decision of the options' rule; `update` holds the unknown statistic and readings.
  Decision Decide(const Assessment& winner, FrameUpdate& update) const;
  // U less what the window's noise and blur add to it: to an unknown object's (the null's
  // allowance) and to a known one's (core/decision/quality_allowance.h).
  struct Judged {
    double as_unknown = 0;
    double as_known = 0;
  };
  Judged JudgedStatistics(const FrameUpdate& update) const;
  // Active vision among the ranked objects scoring within the margin of the winner.
  SuggestedMove SuggestNextMove(std::span<Assessment> ranked);

  std::shared_ptr<const ViewIndexSnapshot> index_;
  std::shared_ptr<const RejectionCalibration> calibration_;
  std::vector<QueryFrame> window_;  // oldest first
  // The window frames' similarities with the objects Answer() looks at closely; cleared when
  // the snapshot changes.
  std::unique_ptr<SimilarityRows> rows_;
  std::int64_t frames_seen_ = 0;
};

}  // namespace orbit
