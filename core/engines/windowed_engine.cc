#include "core/engines/windowed_engine.h"

#include <algorithm>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/decision/confidence.h"
#include "core/decision/quality_allowance.h"
#include "core/decision/rejection_calibration.h"
#include "core/decision/unknown_statistic.h"
#include "core/index/similarity_rows.h"

namespace orbit {

WindowedEngine::WindowedEngine(std::string_view name, const EngineOptions& options)
    : RecognitionEngine(name, options), rows_(std::make_unique<SimilarityRows>()) {
  window_.reserve(options.window);
}

WindowedEngine::~WindowedEngine() = default;

void WindowedEngine::Rebase(const ViewIndexSnapshot&, const ViewIndexSnapshot& after,
                            const SnapshotChange&, std::span<const QueryFrame> window) {
  Clear();
  for (const QueryFrame& frame : window) Append(after, frame);
}

void WindowedEngine::Complete(const ViewIndexSnapshot&, std::span<const QueryFrame>,
                              const ObjectRows&, Assessment&) {}

void WindowedEngine::Validate(const ViewIndexSnapshot* index, const QueryFrame& frame) const {
  if (index == nullptr) throw std::invalid_argument("no view index to recognise against");
  if (frame.descriptor.variant != index->variant()) {
    throw std::invalid_argument(
        "frame descriptor has variant " + std::string(VariantName(frame.descriptor.variant)) +
        ", the model set has " + std::string(VariantName(index->variant())));
  }
  ValidateQueryFrame(frame);
}

void WindowedEngine::Push(const QueryFrame& frame) {
  if (static_cast<int>(window_.size()) == options().window) {
    DropOldest();
    window_.erase(window_.begin());
    rows_->DropOldest();
  }
  window_.push_back(frame);
  rows_->PushFrame();
  Append(*index_, frame);
  ++frames_seen_;
}

FrameUpdate WindowedEngine::Observe(std::shared_ptr<const ViewIndexSnapshot> index,
                                    const QueryFrame& frame) {
  Validate(index.get(), frame);
  if (index != index_) {
    // A new model set: bring the frames still in the window to it.
    if (window_.empty()) {
      Clear();
    } else {
      const auto change = index->ChangeSince(*index_);
      Rebase(*index_, *index, *change, window_);
      // The rows of objects both snapshots share stay right; the removed objects' go (they are
      // alive until index_ is replaced, so no added object can have their address).
      rows_->Forget(change->removed);
    }
    index_ = std::move(index);
  }
  Push(frame);
  return Answer();
}

FrameUpdate WindowedEngine::ObserveSequence(std::shared_ptr<const ViewIndexSnapshot> index,
                                            std::span<const QueryFrame> frames) {
  Reset();
  if (frames.empty()) throw std::invalid_argument("ObserveSequence needs at least one frame");
  for (const QueryFrame& frame : frames) Validate(index.get(), frame);
  index_ = std::move(index);
  // Only the last `window` frames can matter; the earlier ones still count in frame_index.
  const std::size_t skipped = frames.size() > static_cast<std::size_t>(options().window)
                                  ? frames.size() - options().window
                                  : 0;
  frames_seen_ = static_cast<std::int64_t>(skipped);
  for (const QueryFrame& frame : frames.subspan(skipped)) Push(frame);
  return Answer();
}

void WindowedEngine::SetCalibration(std::shared_ptr<const RejectionCalibration> calibration) {
  calibration_ = std::move(calibration);
}

void WindowedEngine::Reset() {
  Clear();
  window_.clear();
  rows_->Clear();
  index_.reset();
  frames_seen_ = 0;
}

FrameUpdate WindowedEngine::Answer() {
  FrameUpdate update;
  update.frame_index = frames_seen_ - 1;
  std::vector<Assessment> assessments = Assess(*index_, window_);
  if (assessments.empty()) return update;
  const std::size_t ordered = Rank(assessments);
  const std::size_t shown = std::min<std::size_t>(assessments.size(), options().top_k);
  for (std::size_t i = 0; i < shown; ++i) {
    update.ranking.push_back({assessments[i].object->id(), assessments[i].score});
  }
  Judge(assessments.front(), ordered > 1 ? &assessments[1] : nullptr, update);
  update.move = SuggestNextMove(std::span(assessments).first(shown));
  return update;
}

std::size_t WindowedEngine::Rank(std::vector<Assessment>& assessments) {
  // Only the ranked objects need ordering (an HMM session assesses every object per frame), and
  // the runner-up for the unknown statistic.
  const std::size_t ordered = std::min<std::size_t>(
      assessments.size(),
      std::max<std::size_t>(static_cast<std::size_t>(RankedDepth(options())), 2));
  const auto better = [](const Assessment& a, const Assessment& b) {
    return a.score > b.score || (a.score == b.score && a.object->id() < b.object->id());
  };
  const auto ranked = assessments.begin() + static_cast<std::ptrdiff_t>(ordered);
  std::partial_sort(assessments.begin(), ranked, assessments.end(), better);
  const double weight = options().nearest_view_weight;
  if (weight > 0) {
    for (auto it = assessments.begin(); it != ranked; ++it) {
      double nearest = 0;
      for (const NearestView& view : rows_->For(window_, *it->object).nearest) {
        nearest += view.closest();
      }
      nearest /= static_cast<double>(window_.size());
      it->score = (1 - weight) * it->score + weight * nearest;
    }
    std::sort(assessments.begin(), ranked, better);
  }
  return ordered;
}

void WindowedEngine::Judge(Assessment& winner, const Assessment* runner_up, FrameUpdate& update) {
  const ObjectRows winner_rows = rows_->For(window_, *winner.object);
  Prefetch(winner_rows);
  Complete(*index_, window_, winner_rows, winner);
  if (runner_up != nullptr) {
    const ObjectRows runner_up_rows = rows_->For(window_, *runner_up->object);
    update.unknown_statistic = UnknownStatistic(winner_rows, &runner_up_rows);
  } else {
    update.unknown_statistic = UnknownStatistic(winner_rows, nullptr);
  }
  std::vector<std::optional<double>> noise, blur;
  for (const QueryFrame& frame : window_) {
    noise.push_back(frame.noise_sigma);
    blur.push_back(frame.blur);
  }
  update.noise_sigma = MeanReading(noise);
  update.blur = MeanReading(blur);
  const int frames = static_cast<int>(window_.size());
  if (calibration_ != nullptr && calibration_->calibrated() && calibration_->has_known_windows()) {
    const Judged judged = JudgedStatistics(update);
    update.confidence =
        CatalogueConfidence(*calibration_, judged.as_known, judged.as_unknown, frames);
  } else {
    update.confidence = Confidence(update.unknown_statistic, frames);
  }
  update.decision = Decide(winner, update);
  update.pose = EstimatePose(window_, winner_rows);
}

WindowedEngine::Judged WindowedEngine::JudgedStatistics(const FrameUpdate& update) const {
  const DescriptorVariant variant = index_->variant();
  return {update.unknown_statistic -
              WindowAllowance(update.noise_sigma, update.blur, AllowanceSlopesFor(variant)),
          update.unknown_statistic -
              WindowAllowance(update.noise_sigma, update.blur, KnownAllowanceSlopesFor(variant))};
}

Decision WindowedEngine::Decide(const Assessment& winner, FrameUpdate& update) const {
  const EngineOptions& o = options();
  if (calibration_ != nullptr && calibration_->calibrated()) {
    // The calibrated rule judges U less what the window's noise and blur alone add to it: the
    // null's rise against the null's quantile, the known objects' against the known ceiling
    // (core/decision/rejection_calibration.h).
    const int frames = static_cast<int>(window_.size());
    const Judged judged = JudgedStatistics(update);
    update.unknown_p_value = calibration_->FalseAcceptRate(judged.as_unknown, frames);
    if (o.rejection == RejectionRule::kCalibrated) {
      return judged.as_unknown <= calibration_->Threshold(frames, o.false_accept_rate,
                                                          o.known_accept_rate) &&
                     judged.as_known <= calibration_->KnownCeiling(frames)
                 ? Decision::kAccept
                 : Decision::kUnknown;
    }
  }
  if (o.rejection != RejectionRule::kTypicalDistance) return Decision::kUndecided;
  std::vector<MatchedDistance> distances;
  for (const MatchedView& match : winner.matched) {
    distances.push_back(
        {1.0 - match.similarity, winner.object->model().views[match.view].typical_distance});
  }
  return DecideRecognition(distances, o.threshold);
}

SuggestedMove WindowedEngine::SuggestNextMove(std::span<Assessment> ranked) {
  const Assessment& winner = ranked.front();
  std::vector<MoveCandidate> candidates{{winner.object, winner.latest_azimuth}};
  for (std::size_t i = 1; i < ranked.size(); ++i) {
    if (ranked[i].score < winner.score - options().ambiguity_margin) break;
    Complete(*index_, window_, rows_->For(window_, *ranked[i].object), ranked[i]);
    candidates.push_back({ranked[i].object, ranked[i].latest_azimuth});
  }
  std::vector<double> seen_turns;
  for (std::size_t k = 0; options().move_prefers_new_side && k + 1 < window_.size(); ++k) {
    if (const std::optional<double> turn = MeasuredTurn(window_.back(), window_[k])) {
      seen_turns.push_back(*turn);
    }
  }
  return SuggestMove(candidates, options().averaged_views, seen_turns);
}

}  // namespace orbit
