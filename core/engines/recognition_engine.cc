#include "core/engines/recognition_engine.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/decision/active_vision.h"
#include "core/base/angles.h"
#include "core/engines/baseline_engines.h"
#include "core/decision/confidence.h"
#include "core/engines/hough_voter.h"
#include "core/decision/quality_allowance.h"
#include "core/engines/orientation_hmm.h"
#include "core/decision/pose_estimate.h"
#include "core/decision/rejection.h"
#include "core/decision/rejection_calibration.h"
#include "core/descriptor/similarity.h"
#include "core/index/similarity_rows.h"
#include "core/decision/unknown_statistic.h"

namespace orbit {
namespace {

constexpr std::array<std::string_view, 7> kEngineNames = {"eis", "siis",   "eiis", "vci-bm",
                                                          "vci-w0", "vci", "hmm"};

void Require(bool condition, const std::string& message) {
  if (!condition) throw std::invalid_argument("engine option " + message);
}

}  // namespace

void ValidateEngineOptions(const EngineOptions& o) {
  Require(o.window >= 1 && o.window <= kMaxWindow,
          "window must be in 1.." + std::to_string(kMaxWindow) + ", got " + std::to_string(o.window));
  Require(o.list_length >= 1, "list_length (N_L) must be at least 1");
  Require(o.orientation_weight >= 0 && o.orientation_weight <= kMaxOrientationWeight,
          "orientation_weight (w) must be in [0, " +
              std::to_string(static_cast<int>(kMaxOrientationWeight)) + "]");
  Require(o.hmm_sharpness >= 0 && o.hmm_sharpness <= kMaxHmmSharpness,
          "hmm_sharpness must be in 0.." + std::to_string(kMaxHmmSharpness));
  Require(o.hmm_states >= 1 && o.hmm_states <= kMaxHmmStates,
          "hmm_states must be in 1.." + std::to_string(kMaxHmmStates));
  Require(std::isfinite(o.threshold) && o.threshold > 0, "threshold (Th) must be finite and > 0");
  Require(o.false_accept_rate > 0 && o.false_accept_rate < 1,
          "false_accept_rate must be in (0, 1)");
  Require(o.top_k >= 1, "top_k must be at least 1");
  Require(o.nearest_view_weight >= 0 && o.nearest_view_weight <= 1,
          "nearest_view_weight must be in [0, 1]");
  Require(o.averaged_views >= 2 && o.averaged_views <= 360, "averaged_views must be in 2..360");
  Require(std::isfinite(o.ambiguity_margin) && o.ambiguity_margin >= 0,
          "ambiguity_margin must be finite and >= 0");
}

int RankedDepth(const EngineOptions& options) {
  return options.nearest_view_weight > 0 ? std::max(options.top_k, kNearestViewCandidates)
                                         : options.top_k;
}


RecognitionEngine::RecognitionEngine(std::string_view name, const EngineOptions& options)
    : name_(name), options_(options) {
  ValidateEngineOptions(options_);
  window_.reserve(options_.window);
  rows_ = std::make_unique<SimilarityRows>();
}

RecognitionEngine::~RecognitionEngine() = default;

void RecognitionEngine::Rebase(const ViewIndexSnapshot&, const ViewIndexSnapshot& after,
                               const SnapshotChange&, std::span<const QueryFrame> window) {
  Clear();
  for (const QueryFrame& frame : window) Append(after, frame);
}

void RecognitionEngine::Complete(const ViewIndexSnapshot&, std::span<const QueryFrame>,
                                 const ObjectRows&, Assessment&) {}

void RecognitionEngine::Validate(const ViewIndexSnapshot* index, const QueryFrame& frame) const {
  if (index == nullptr) throw std::invalid_argument("no view index to recognise against");
  if (frame.descriptor.variant != index->variant()) {
    throw std::invalid_argument("frame descriptor has variant " +
                                std::string(VariantName(frame.descriptor.variant)) +
                                ", the model set has " + std::string(VariantName(index->variant())));
  }
  ValidateDescriptorValues(frame.descriptor.values, "frame descriptor");
  if (frame.azimuth && !std::isfinite(*frame.azimuth)) {
    throw std::invalid_argument("frame azimuth is not finite");
  }
  if (frame.noise_sigma && !(*frame.noise_sigma >= 0 && *frame.noise_sigma <= kMaxNoiseSigma)) {
    throw std::invalid_argument("frame noise sigma must be in [0, " +
                                std::to_string(static_cast<int>(kMaxNoiseSigma)) + "]");
  }
  if (frame.blur && !(*frame.blur >= 0 && *frame.blur <= kMaxBlur)) {
    throw std::invalid_argument("frame blur must be in [0, " +
                                std::to_string(static_cast<int>(kMaxBlur)) + "]");
  }
}

void RecognitionEngine::Push(const QueryFrame& frame) {
  if (static_cast<int>(window_.size()) == options_.window) {
    DropOldest();
    window_.erase(window_.begin());
    rows_->DropOldest();
  }
  window_.push_back(frame);
  rows_->PushFrame();
  Append(*index_, frame);
  ++frames_seen_;
}

FrameUpdate RecognitionEngine::Observe(std::shared_ptr<const ViewIndexSnapshot> index,
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

FrameUpdate RecognitionEngine::ObserveSequence(std::shared_ptr<const ViewIndexSnapshot> index,
                                               std::span<const QueryFrame> frames) {
  Reset();
  if (frames.empty()) throw std::invalid_argument("ObserveSequence needs at least one frame");
  for (const QueryFrame& frame : frames) Validate(index.get(), frame);
  index_ = std::move(index);
  // Only the last `window` frames can matter; the earlier ones still count in frame_index.
  const std::size_t skipped = frames.size() > static_cast<std::size_t>(options_.window)
                                  ? frames.size() - options_.window
                                  : 0;
  frames_seen_ = static_cast<std::int64_t>(skipped);
  for (const QueryFrame& frame : frames.subspan(skipped)) Push(frame);
  return Answer();
}

void RecognitionEngine::SetCalibration(std::shared_ptr<const RejectionCalibration> calibration) {
  calibration_ = std::move(calibration);
}

void RecognitionEngine::Reset() {
  Clear();
  window_.clear();
  rows_->Clear();
  index_.reset();
  frames_seen_ = 0;
}

FrameUpdate RecognitionEngine::Answer() {
  FrameUpdate update;
  update.frame_index = frames_seen_ - 1;
  std::vector<Assessment> assessments = Assess(*index_, window_);
  if (assessments.empty()) return update;
  const std::size_t shown = std::min<std::size_t>(assessments.size(), options_.top_k);
  // Only the ranked objects need ordering (an HMM session assesses every object per frame), and
  // the runner-up for the calibrated rule.
  const std::size_t ranked_depth = static_cast<std::size_t>(RankedDepth(options_));
  const std::size_t ordered =
      std::min<std::size_t>(assessments.size(), std::max<std::size_t>(ranked_depth, 2));
  const auto better = [](const Assessment& a, const Assessment& b) {
    return a.score > b.score || (a.score == b.score && a.object->id() < b.object->id());
  };
  const auto ranked = assessments.begin() + static_cast<std::ptrdiff_t>(ordered);
  std::partial_sort(assessments.begin(), ranked, assessments.end(), better);
  if (options_.nearest_view_weight > 0) {
    const double weight = options_.nearest_view_weight;
    for (auto it = assessments.begin(); it != ranked; ++it) {
      double nearest = 0;
      for (const NearestView& view : rows_->For(window_, *it->object).nearest) {
        nearest += view.similarity;
      }
      nearest /= static_cast<double>(window_.size());
      it->score = (1 - weight) * it->score + weight * nearest;
    }
    std::sort(assessments.begin(), ranked, better);
  }
  for (std::size_t i = 0; i < shown; ++i) {
    update.ranking.push_back({assessments[i].object->id(), assessments[i].score});
  }

  // Recognition: accept or unknown, by the options' rule.
  Assessment& winner = assessments.front();
  const ObjectRows winner_rows = rows_->For(window_, *winner.object);
  Prefetch(winner_rows);
  Complete(*index_, window_, winner_rows, winner);
  if (ordered > 1) {
    const ObjectRows runner_up_rows = rows_->For(window_, *assessments[1].object);
    update.unknown_statistic = UnknownStatistic(winner_rows, &runner_up_rows);
  } else {
    update.unknown_statistic = UnknownStatistic(winner_rows, nullptr);
  }
  update.confidence = Confidence(update.unknown_statistic, static_cast<int>(window_.size()));
  std::vector<std::optional<double>> noise, blur;
  for (const QueryFrame& frame : window_) {
    noise.push_back(frame.noise_sigma);
    blur.push_back(frame.blur);
  }
  update.noise_sigma = MeanReading(noise);
  update.blur = MeanReading(blur);
  const bool calibrated = calibration_ != nullptr && calibration_->calibrated();
  const int frames = static_cast<int>(window_.size());
  if (calibrated) {
    // The calibrated rule judges U less what the window's noise and blur alone add to it.
    const double allowance = (update.noise_sigma ? NoiseAllowance(*update.noise_sigma) : 0.0) +
                             (update.blur ? BlurAllowance(*update.blur) : 0.0);
    const double judged = update.unknown_statistic - allowance;
    update.unknown_p_value = calibration_->FalseAcceptRate(judged, frames);
    if (options_.rejection == RejectionRule::kCalibrated) {
      update.decision = judged <= calibration_->Threshold(frames, options_.false_accept_rate)
                            ? Decision::kAccept
                            : Decision::kUnknown;
    }
  }
  if (options_.rejection == RejectionRule::kTypicalDistance) {
    std::vector<MatchedDistance> distances;
    for (const MatchedView& match : winner.matched) {
      distances.push_back({1.0 - match.similarity,
                           winner.object->model().views[match.view].typical_distance});
    }
    update.decision = DecideRecognition(distances, options_.threshold);
  }
  update.pose = EstimatePose(window_, winner_rows);

  // Active vision among the objects scoring within the margin of the winner.
  std::vector<MoveCandidate> candidates{{winner.object, winner.latest_azimuth}};
  for (std::size_t i = 1; i < shown; ++i) {
    if (assessments[i].score < winner.score - options_.ambiguity_margin) break;
    Complete(*index_, window_, rows_->For(window_, *assessments[i].object), assessments[i]);
    candidates.push_back({assessments[i].object, assessments[i].latest_azimuth});
  }
  std::vector<double> seen_turns;
  for (std::size_t k = 0; options_.move_prefers_new_side && k + 1 < window_.size(); ++k) {
    if (const std::optional<double> turn = MeasuredTurn(window_.back(), window_[k])) {
      seen_turns.push_back(*turn);
    }
  }
  update.move = SuggestMove(candidates, options_.averaged_views, seen_turns);
  return update;
}

std::unique_ptr<RecognitionEngine> CreateEngine(std::string_view name,
                                                const EngineOptions& options) {
  if (name == "eis") return MakeBaselineEngine(BaselineMethod::kEis, options);
  if (name == "siis") return MakeBaselineEngine(BaselineMethod::kSiis, options);
  if (name == "eiis") return MakeBaselineEngine(BaselineMethod::kEiis, options);
  if (name == "vci-bm") return MakeHoughEngine(HoughVariant::kBestMatch, options);
  if (name == "vci-w0") return MakeHoughEngine(HoughVariant::kWeightless, options);
  if (name == "vci") return MakeHoughEngine(HoughVariant::kOriented, options);
  if (name == "hmm") return MakeHmmEngine(options);
  std::string known;
  for (const std::string_view n : kEngineNames) known += (known.empty() ? "" : ", ") + std::string(n);
  throw std::invalid_argument("unknown engine \"" + std::string(name) + "\" (known: " + known + ")");
}

std::span<const std::string_view> EngineNames() { return kEngineNames; }

}  // namespace orbit
