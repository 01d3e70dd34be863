#include "core/engines/baseline_engines.h"

#include <deque>
#include <optional>
#include <unordered_map>
#include <vector>

#include "core/base/angles.h"
#include "core/descriptor/similarity.h"
#include "core/engines/windowed_engine.h"

namespace orbit {
namespace {

class BaselineEngine final : public WindowedEngine {
 public:
  BaselineEngine(BaselineMethod method, const EngineOptions& options)
      : WindowedEngine(Name(method), options), method_(method) {}

 protected:
  void Append(const ViewIndexSnapshot& index, const QueryFrame& frame) override {
    similarities_.emplace_back();
    index.SimilarityToEveryView(frame.descriptor.values, similarities_.back());
  }
  void DropOldest() override { similarities_.pop_front(); }
  void Clear() override { similarities_.clear(); }

  // Kept objects' similarities move to their new slots; added objects' views are scored.
  void Rebase(const ViewIndexSnapshot& before, const ViewIndexSnapshot& after,
              const SnapshotChange&, std::span<const QueryFrame> window) override {
    std::unordered_map<const IndexedObject*, std::size_t> before_first_slot;
    for (const ObjectSlot& slot : before.objects())
      before_first_slot[slot.object] = slot.first_slot;
    for (std::size_t t = 0; t < similarities_.size(); ++t) {
      std::vector<float> moved(after.slot_count(), 0.0f);
      for (const ObjectSlot& slot : after.objects()) {
        const auto kept = before_first_slot.find(slot.object);
        const int views = slot.object->view_count();
        for (int v = 0; v < views; ++v) {
          moved[slot.first_slot + v] =
              kept != before_first_slot.end()
                  ? similarities_[t][kept->second + v]
                  : static_cast<float>(Tanimoto(window[t].descriptor.values,
                                                slot.object->model().views[v].descriptor));
        }
      }
      similarities_[t] = std::move(moved);
    }
  }

  std::vector<Assessment> Assess(const ViewIndexSnapshot& index,
                                 std::span<const QueryFrame> window) override {
    std::vector<Assessment> assessments;
    assessments.reserve(index.object_count());
    for (const ObjectSlot& slot : index.objects()) {
      switch (method_) {
        case BaselineMethod::kEis: assessments.push_back(AssessEis(slot)); break;
        case BaselineMethod::kSiis: assessments.push_back(AssessSiis(slot, window)); break;
        case BaselineMethod::kEiis: assessments.push_back(AssessEiis(slot, window)); break;
      }
    }
    return assessments;
  }

 private:
  static std::string_view Name(BaselineMethod method) {
    switch (method) {
      case BaselineMethod::kEis: return "eis";
      case BaselineMethod::kSiis: return "siis";
      case BaselineMethod::kEiis: break;
    }
    return "eiis";
  }

  float Similarity(int frame, const ObjectSlot& slot, int view) const {
    return similarities_[frame][slot.first_slot + view];
  }

  // The view of frame k's object at the most similar of the object's views.
  int BestView(int frame, const ObjectSlot& slot) const {
    int best = 0;
    for (int v = 1; v < slot.object->view_count(); ++v) {
      if (Similarity(frame, slot, v) > Similarity(frame, slot, best)) best = v;
    }
    return best;
  }

  Assessment Finish(const ObjectSlot& slot, std::vector<MatchedView> matched) const {
    Assessment a;
    a.object = slot.object;
    double sum = 0;
    for (const MatchedView& m : matched) sum += m.similarity;
    a.score = sum / static_cast<double>(matched.size());
    a.latest_azimuth = slot.object->model().views[matched.back().view].azimuth;
    a.matched = std::move(matched);
    return a;
  }

  Assessment AssessEis(const ObjectSlot& slot) const {
    std::vector<MatchedView> matched;
    for (int k = 0; k < static_cast<int>(similarities_.size()); ++k) {
      const int view = BestView(k, slot);
      matched.push_back({k, view, Similarity(k, slot, view)});
    }
    return Finish(slot, std::move(matched));
  }

  // Frames matched through the IMU to the views at the orientations implied by `anchor`, the
  // view facing the camera at the oldest frame; returns the sum of similarities.
  double MatchFromAnchor(const ObjectSlot& slot, std::span<const QueryFrame> window, int anchor,
                         std::vector<MatchedView>* matched) const {
    const double anchor_azimuth = slot.object->model().views[anchor].azimuth;
    double sum = Similarity(0, slot, anchor);
    if (matched != nullptr) matched->push_back({0, anchor, Similarity(0, slot, anchor)});
    for (int k = 1; k < static_cast<int>(window.size()); ++k) {
      // Without a measured turn, the frame's most similar view (as EIS matches every frame).
      const std::optional<double> turn = MeasuredTurn(window[0], window[k]);
      int view = 0;
      if (turn) {
        const auto [left, right] = slot.object->NeighbourViews(anchor_azimuth + *turn);
        view = Similarity(k, slot, right) > Similarity(k, slot, left) ? right : left;
      } else {
        view = BestView(k, slot);
      }
      sum += Similarity(k, slot, view);
      if (matched != nullptr) matched->push_back({k, view, Similarity(k, slot, view)});
    }
    return sum;
  }

  Assessment AssessSiis(const ObjectSlot& slot, std::span<const QueryFrame> window) const {
    std::vector<MatchedView> matched;
    MatchFromAnchor(slot, window, BestView(0, slot), &matched);
    return Finish(slot, std::move(matched));
  }

  Assessment AssessEiis(const ObjectSlot& slot, std::span<const QueryFrame> window) const {
    int best_anchor = 0;
    double best_sum = -1;
    for (const int anchor : slot.object->views_by_azimuth()) {
      const double sum = MatchFromAnchor(slot, window, anchor, nullptr);
      if (sum > best_sum) {
        best_sum = sum;
        best_anchor = anchor;
      }
    }
    std::vector<MatchedView> matched;
    MatchFromAnchor(slot, window, best_anchor, &matched);
    return Finish(slot, std::move(matched));
  }

  const BaselineMethod method_;
  std::deque<std::vector<float>> similarities_;  // per window frame, per view slot
};

}  // namespace

std::unique_ptr<RecognitionEngine> MakeBaselineEngine(BaselineMethod method,
                                                      const EngineOptions& options) {
  return std::make_unique<BaselineEngine>(method, options);
}

}  // namespace orbit
