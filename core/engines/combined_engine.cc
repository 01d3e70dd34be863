#include "core/engines/combined_engine.h"

#include <algorithm>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/engines/hough_voter.h"
#include "core/engines/orientation_hmm.h"

namespace orbit {
namespace {

class CombinedEngine final : public RecognitionEngine {
 public:
  CombinedEngine(std::string_view name, const EngineOptions& options,
                 std::vector<std::unique_ptr<RecognitionEngine>> engines)
      : RecognitionEngine(name, options), engines_(std::move(engines)) {}

  FrameUpdate Observe(std::shared_ptr<const ViewIndexSnapshot> index,
                      const QueryFrame& frame) override {
    // Every engine validates a frame alike, so the first throws before any changes state.
    std::vector<FrameUpdate> updates;
    for (auto& engine : engines_) updates.push_back(engine->Observe(index, frame));
    return Combine(updates);
  }

  FrameUpdate ObserveSequence(std::shared_ptr<const ViewIndexSnapshot> index,
                              std::span<const QueryFrame> frames) override {
    std::vector<FrameUpdate> updates;
    for (auto& engine : engines_) updates.push_back(engine->ObserveSequence(index, frames));
    return Combine(updates);
  }

  void Reset() override {
    for (auto& engine : engines_) engine->Reset();
  }

  void SetCalibration(std::shared_ptr<const RejectionCalibration> calibration) override {
    for (auto& engine : engines_) engine->SetCalibration(calibration);
  }

 private:
  FrameUpdate Combine(const std::vector<FrameUpdate>& updates) const {
    std::unordered_map<ObjectId, double> sum;
    for (const FrameUpdate& u : updates) {
      for (const RankedObject& r : u.ranking) sum[r.object] += r.score;
    }
    FrameUpdate combined;
    combined.frame_index = updates[0].frame_index;
    combined.move = updates[0].move;
    combined.noise_sigma = updates[0].noise_sigma;
    combined.blur = updates[0].blur;
    for (const auto& [object, total] : sum) {
      combined.ranking.push_back({object, total / static_cast<double>(updates.size())});
    }
    std::sort(combined.ranking.begin(), combined.ranking.end(),
              [](const RankedObject& a, const RankedObject& b) {
                return a.score != b.score ? a.score > b.score : a.object < b.object;
              });
    if (static_cast<int>(combined.ranking.size()) > options().top_k) {
      combined.ranking.resize(options().top_k);
    }
    if (combined.ranking.empty()) return combined;
    for (const FrameUpdate& u : updates) {
      if (!u.ranking.empty() && u.ranking[0].object == combined.ranking[0].object) {
        combined.decision = u.decision;
        combined.unknown_statistic = u.unknown_statistic;
        combined.unknown_p_value = u.unknown_p_value;
        combined.confidence = u.confidence;
        combined.pose = u.pose;
        break;
      }
    }
    return combined;
  }

  std::vector<std::unique_ptr<RecognitionEngine>> engines_;  // VCI first
};

}  // namespace

std::unique_ptr<RecognitionEngine> MakeVciHmmEngine(const EngineOptions& options) {
  EngineOptions deeper = options;
  deeper.top_k = std::max(options.top_k, kCombinedDepth);
  std::vector<std::unique_ptr<RecognitionEngine>> engines;
  engines.push_back(MakeHoughEngine(HoughVariant::kOriented, deeper));
  engines.push_back(MakeHmmEngine(deeper));
  return std::make_unique<CombinedEngine>("vci-hmm", options, std::move(engines));
}

}  // namespace orbit
