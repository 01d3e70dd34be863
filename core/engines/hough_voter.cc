#include "core/engines/hough_voter.h"

#include <algorithm>
#include <deque>
#include <limits>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>

#include "core/base/angles.h"
#include "core/descriptor/similarity.h"
#include "core/engines/windowed_engine.h"

namespace orbit {

double OrientationMismatch(double beta_k, double beta_next, double alpha_k, double alpha_next) {
  // AzimuthChange(next, k) = WrapDegrees(k - next), without overflow for far-apart readings.
  const double d_beta = AzimuthChange(beta_next, beta_k);
  const double d_alpha = AzimuthChange(alpha_next, alpha_k);
  return DegreesToRadians(std::abs(WrapDegrees(d_beta - d_alpha)));
}

namespace {

// w x the orientation term of the step from an entry of frame k to one of frame k + 1; 0 when a
// frame has no azimuth (the turn is unknown, so no path is preferred for it).
double StepCost(const HoughEntry& here, const HoughEntry& next,
                const std::optional<double>& alpha_k, const std::optional<double>& alpha_next,
                double w) {
  if (!alpha_k || !alpha_next || w == 0) return 0;
  return w * OrientationMismatch(here.azimuth, next.azimuth, *alpha_k, *alpha_next);
}

}  // namespace

double HoughPathScore(std::span<const std::vector<HoughEntry>> entries,
                      std::span<const std::optional<double>> frame_azimuths,
                      std::span<const int> choice, double w) {
  double score = 0;
  for (std::size_t k = 0; k < entries.size(); ++k) {
    const HoughEntry& here = entries[k][choice[k]];
    score += here.similarity;
    if (k + 1 < entries.size()) {
      const HoughEntry& next = entries[k + 1][choice[k + 1]];
      score -= StepCost(here, next, frame_azimuths[k], frame_azimuths[k + 1], w);
    }
  }
  return score;
}

HoughPath BestHoughPath(std::span<const std::vector<HoughEntry>> entries,
                        std::span<const std::optional<double>> frame_azimuths, double w) {
  if (entries.empty()) throw std::invalid_argument("BestHoughPath: no frames");
  if (entries.size() != frame_azimuths.size()) {
    throw std::invalid_argument("BestHoughPath: one azimuth per frame is needed");
  }
  for (const auto& list : entries) {
    if (list.empty()) throw std::invalid_argument("BestHoughPath: a frame has no entry");
  }
  // best[k][j]: the best score of a path over frames 0..k ending at entry j of frame k;
  // from[k][j]: the entry of frame k-1 on that path.
  const std::size_t n = entries.size();
  std::vector<std::vector<double>> best(n);
  std::vector<std::vector<int>> from(n);
  for (const HoughEntry& e : entries[0]) best[0].push_back(e.similarity);
  for (std::size_t k = 1; k < n; ++k) {
    for (const HoughEntry& e : entries[k]) {
      double top = -std::numeric_limits<double>::infinity();
      int arg = 0;
      for (std::size_t i = 0; i < entries[k - 1].size(); ++i) {
        const double value = best[k - 1][i] - StepCost(entries[k - 1][i], e, frame_azimuths[k - 1],
                                                       frame_azimuths[k], w);
        if (value > top) {
          top = value;
          arg = static_cast<int>(i);
        }
      }
      best[k].push_back(top + e.similarity);
      from[k].push_back(arg);
    }
  }
  HoughPath path;
  path.choice.assign(n, 0);
  int last = 0;
  for (std::size_t j = 1; j < best[n - 1].size(); ++j) {
    if (best[n - 1][j] > best[n - 1][last]) last = static_cast<int>(j);
  }
  path.score = best[n - 1][last];
  path.choice[n - 1] = last;
  for (std::size_t k = n - 1; k > 0; --k) path.choice[k - 1] = from[k][path.choice[k]];
  return path;
}

namespace {

class HoughVoter final : public WindowedEngine {
 public:
  HoughVoter(HoughVariant variant, const EngineOptions& options)
      : WindowedEngine(Name(variant), options), variant_(variant) {}

 protected:
  void Append(const ViewIndexSnapshot& index, const QueryFrame& frame) override {
    lists_.push_back(index.Search(frame.descriptor.values, options().list_length));
    most_similar_.emplace_back();
  }
  void DropOldest() override {
    lists_.pop_front();
    most_similar_.pop_front();
  }
  void Clear() override {
    lists_.clear();
    most_similar_.clear();
  }

  // A list that held a removed object is searched again (a view beyond its end may now belong
  // in it); any other list only merges the added objects' views that beat its entries. Equal
  // similarities keep the index's order: kept objects before added ones (added last).
  void Rebase(const ViewIndexSnapshot&, const ViewIndexSnapshot& after,
              const SnapshotChange& change, std::span<const QueryFrame> window) override {
    std::unordered_set<ObjectId> removed;
    for (const IndexedObject* object : change.removed) removed.insert(object->id());
    const auto was_removed = [&](const ViewMatch& m) { return removed.contains(m.object); };
    for (std::size_t k = 0; k < lists_.size(); ++k) {
      const DescriptorValues& query = window[k].descriptor.values;
      for (const ObjectId id : removed) most_similar_[k].erase(id);
      std::vector<ViewMatch>& list = lists_[k];
      if (std::any_of(list.begin(), list.end(), was_removed)) {
        list = after.Search(query, options().list_length);
        continue;
      }
      for (const ObjectSlot& slot : change.added) {
        const auto& views = slot.object->model().views;
        for (int v = 0; v < static_cast<int>(views.size()); ++v) {
          list.push_back(
              {slot.object->id(), v, views[v].azimuth, Tanimoto(query, views[v].descriptor)});
        }
      }
      std::stable_sort(list.begin(), list.end(), [](const ViewMatch& a, const ViewMatch& b) {
        return a.similarity > b.similarity;
      });
      if (static_cast<int>(list.size()) > options().list_length) list.resize(options().list_length);
    }
  }

  std::vector<Assessment> Assess(const ViewIndexSnapshot& index,
                                 std::span<const QueryFrame> window) override {
    // Candidates in order of first appearance, with their entries per frame.
    std::vector<ObjectId> order;
    std::unordered_map<ObjectId, std::vector<std::vector<HoughEntry>>> entries;
    for (std::size_t k = 0; k < lists_.size(); ++k) {
      for (const ViewMatch& match : lists_[k]) {
        auto [it, inserted] = entries.try_emplace(match.object);
        if (inserted) {
          order.push_back(match.object);
          it->second.resize(lists_.size());
        }
        it->second[k].push_back({match.view, match.azimuth, match.similarity});
      }
    }
    std::vector<Assessment> assessments;
    for (const ObjectId id : order) {
      const IndexedObject* object = index.Find(id);
      if (variant_ == HoughVariant::kBestMatch) {
        assessments.push_back(AssessBestMatch(*object, entries[id], window));
      } else {
        assessments.push_back(AssessPaths(*object, entries[id], window));
      }
    }
    return assessments;
  }

 private:
  static std::string_view Name(HoughVariant variant) {
    switch (variant) {
      case HoughVariant::kBestMatch: return "vci-bm";
      case HoughVariant::kWeightless: return "vci-w0";
      case HoughVariant::kOriented: break;
    }
    return "vci";
  }

  Assessment AssessBestMatch(const IndexedObject& object,
                             const std::vector<std::vector<HoughEntry>>& entries,
                             std::span<const QueryFrame> window) const {
    Assessment a;
    a.object = &object;
    double sum = 0;
    int latest_frame = 0;
    for (std::size_t k = 0; k < entries.size(); ++k) {
      if (entries[k].empty()) continue;
      const HoughEntry& best = entries[k].front();  // lists are sorted best first
      sum += best.similarity;
      a.matched.push_back({static_cast<int>(k), best.view, best.similarity});
      a.latest_azimuth = best.azimuth;
      latest_frame = static_cast<int>(k);
    }
    // The latest view's azimuth, turned by what the device measured since; as it is without.
    a.latest_azimuth += MeasuredTurn(window[latest_frame], window.back()).value_or(0);
    a.score = sum / static_cast<double>(window.size());
    return a;
  }

  Assessment AssessPaths(const IndexedObject& object, std::vector<std::vector<HoughEntry>>& entries,
                         std::span<const QueryFrame> window) {
    // The anchor: the candidate's most similar entry on any list.
    std::size_t anchor_frame = 0;
    const HoughEntry* anchor = nullptr;
    for (std::size_t k = 0; k < entries.size(); ++k) {
      for (const HoughEntry& e : entries[k]) {
        if (anchor == nullptr || e.similarity > anchor->similarity) {
          anchor = &e;
          anchor_frame = k;
        }
      }
    }
    const double anchor_azimuth = anchor->azimuth;
    for (std::size_t k = 0; k < entries.size(); ++k) {
      if (!entries[k].empty()) continue;
      const DescriptorValues& query = window[k].descriptor.values;
      const std::optional<double> turn = MeasuredTurn(window[anchor_frame], window[k]);
      if (variant_ == HoughVariant::kWeightless || !turn) {
        entries[k].push_back(MostSimilarView(k, object, query));
      } else {
        const int view = object.NearestView(anchor_azimuth + *turn);
        const ModelView& model_view = object.model().views[view];
        entries[k].push_back({view, model_view.azimuth, Tanimoto(query, model_view.descriptor)});
      }
    }
    std::vector<std::optional<double>> azimuths;
    for (const QueryFrame& frame : window) azimuths.push_back(frame.azimuth);
    const double w = variant_ == HoughVariant::kOriented ? options().orientation_weight : 0.0;
    const HoughPath path = BestHoughPath(entries, azimuths, w);

    Assessment a;
    a.object = &object;
    a.score = path.score / static_cast<double>(window.size());
    for (std::size_t k = 0; k < entries.size(); ++k) {
      const HoughEntry& e = entries[k][path.choice[k]];
      a.matched.push_back({static_cast<int>(k), e.view, e.similarity});
    }
    a.latest_azimuth = entries.back()[path.choice.back()].azimuth;
    return a;
  }

  // The object's view most similar to window frame k, cached for the frame's stay in the window.
  HoughEntry MostSimilarView(std::size_t k, const IndexedObject& object,
                             const DescriptorValues& query) {
    auto [it, inserted] = most_similar_[k].try_emplace(object.id());
    if (inserted) {
      const auto& views = object.model().views;
      HoughEntry best{0, views[0].azimuth, Tanimoto(query, views[0].descriptor)};
      for (int v = 1; v < static_cast<int>(views.size()); ++v) {
        const double tc = Tanimoto(query, views[v].descriptor);
        if (tc > best.similarity) best = {v, views[v].azimuth, tc};
      }
      it->second = best;
    }
    return it->second;
  }

  const HoughVariant variant_;
  std::deque<std::vector<ViewMatch>> lists_;  // L_k per window frame
  std::deque<std::unordered_map<ObjectId, HoughEntry>> most_similar_;
};

}  // namespace

std::unique_ptr<RecognitionEngine> MakeHoughEngine(HoughVariant variant,
                                                   const EngineOptions& options) {
  return std::make_unique<HoughVoter>(variant, options);
}

}  // namespace orbit
