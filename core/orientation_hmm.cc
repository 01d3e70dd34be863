#include "core/orientation_hmm.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <stdexcept>
#include <unordered_map>

#include <xmmintrin.h>  // SSE: part of every x86-64 CPU

#include "core/similarity.h"

namespace orbit {
namespace {

constexpr double kMinusInfinity = -std::numeric_limits<double>::infinity();
constexpr double kEmissionFloor = 1e-12;

double Log(double p) { return p > 0 ? std::log(p) : kMinusInfinity; }

}  // namespace

std::vector<Arc> EqualSectors(int count) {
  if (count < 1) throw std::invalid_argument("an HMM needs at least one state");
  std::vector<Arc> sectors;
  const double width = 360.0 / count;
  for (int s = 0; s < count; ++s) sectors.push_back({s * width, width});
  return sectors;
}

std::vector<double> InitialProbabilities(std::span<const Arc> sectors) {
  std::vector<double> initial;
  for (const Arc& sector : sectors) initial.push_back(sector.width / 360.0);
  return initial;
}

std::vector<std::vector<double>> TransitionMatrix(std::span<const Arc> sectors, double delta) {
  const std::size_t n = sectors.size();
  std::vector<std::vector<double>> a(n, std::vector<double>(n, 0.0));
  for (std::size_t j = 0; j < n; ++j) {
    if (!(sectors[j].width > 0)) throw std::invalid_argument("an HMM sector has no width");
    const Arc shifted{sectors[j].start - WrapDegrees(delta), sectors[j].width};  // L_j
    for (std::size_t i = 0; i < n; ++i) {
      a[i][j] = ArcOverlap(shifted, sectors[i]) / shifted.width;
    }
  }
  return a;
}

std::vector<double> Emissions(std::span<const double> state_similarities) {
  double sum = 0;
  for (const double s : state_similarities) sum += s;
  std::vector<double> b;
  for (const double s : state_similarities) {
    b.push_back(sum > 0 ? s / sum : 1.0 / static_cast<double>(state_similarities.size()));
  }
  return b;
}

ViterbiPath Viterbi(std::span<const double> initial,
                    std::span<const std::vector<std::vector<double>>> transitions,
                    std::span<const std::vector<double>> emissions) {
  const std::size_t n = initial.size();
  const std::size_t frames = emissions.size();
  if (frames == 0) throw std::invalid_argument("Viterbi needs at least one frame");
  if (transitions.size() != frames - 1) {
    throw std::invalid_argument("Viterbi needs one transition matrix between consecutive frames");
  }
  for (const auto& b : emissions) {
    if (b.size() != n) throw std::invalid_argument("Viterbi: emission size differs from states");
  }
  for (const auto& a : transitions) {
    if (a.size() != n) throw std::invalid_argument("Viterbi: transition size differs from states");
    for (const auto& row : a) {
      if (row.size() != n) throw std::invalid_argument("Viterbi: transition matrix not square");
    }
  }
  std::vector<double> score(n), next(n);
  std::vector<std::vector<int>> back(frames, std::vector<int>(n, 0));
  for (std::size_t i = 0; i < n; ++i) score[i] = Log(initial[i]) + Log(emissions[0][i]);
  for (std::size_t t = 1; t < frames; ++t) {
    for (std::size_t j = 0; j < n; ++j) {
      double best = kMinusInfinity;
      int arg = 0;
      for (std::size_t i = 0; i < n; ++i) {
        const double value = score[i] + Log(transitions[t - 1][i][j]);
        if (value > best) {
          best = value;
          arg = static_cast<int>(i);
        }
      }
      next[j] = best + Log(emissions[t][j]);
      back[t][j] = arg;
    }
    score.swap(next);
  }
  ViterbiPath path;
  path.states.assign(frames, 0);
  int last = 0;
  for (std::size_t i = 1; i < n; ++i) {
    if (score[i] > score[last]) last = static_cast<int>(i);
  }
  path.log_probability = score[last];
  path.states[frames - 1] = last;
  for (std::size_t t = frames - 1; t > 0; --t) path.states[t - 1] = back[t][path.states[t]];
  return path;
}

namespace {

// q.c over 144 floats, four lanes at a time.
float Dot(const float* q, const float* c) {
  __m128 sum = _mm_setzero_ps();
  for (int i = 0; i < kDescriptorSize; i += 4) {
    sum = _mm_add_ps(sum, _mm_mul_ps(_mm_loadu_ps(q + i), _mm_loadu_ps(c + i)));
  }
  alignas(16) float lanes[4];
  _mm_store_ps(lanes, sum);
  return (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]);
}

class OrientationHmm final : public RecognitionEngine {
 public:
  explicit OrientationHmm(const EngineOptions& options)
      : RecognitionEngine("hmm", options),
        states_(options.hmm_states),
        sectors_(EqualSectors(states_)),
        log_initial_(states_) {
    const std::vector<double> initial = InitialProbabilities(sectors_);
    for (int i = 0; i < states_; ++i) log_initial_[i] = Log(initial[i]);
  }

 protected:
  void Append(const ViewIndexSnapshot& index, const QueryFrame& frame) override {
    if (positions_.empty() && index.object_count() > 0) CacheStates(index);
    // log b_i(o) for every object's states, and TC(S_i, o) for the winner rule.
    const std::size_t objects = index.object_count();
    alignas(16) float query[kDescriptorSize];
    double query_norm = 0;
    for (int d = 0; d < kDescriptorSize; ++d) {
      query[d] = frame.descriptor.values[d];
      query_norm += query[d] * query[d];
    }
    std::vector<float> similarity(objects * states_);
    std::vector<float> log_emission(objects * states_);
    for (std::size_t o = 0; o < objects; ++o) {
      double sum = 0;
      for (int i = 0; i < states_; ++i) {
        const std::size_t s = o * states_ + i;
        const double qc = Dot(query, &state_descriptors_[s * kDescriptorSize]);
        const double denominator = query_norm + state_norms_[s] - qc;
        const double tc = (query_norm == 0 && state_norms_[s] == 0) ? 1.0
                          : denominator > 0                         ? qc / denominator
                                                                    : 0.0;
        similarity[s] = static_cast<float>(tc);
        sum += tc;
      }
      for (int i = 0; i < states_; ++i) {
        const std::size_t s = o * states_ + i;
        const double b = sum > 0 ? similarity[s] / sum : 1.0 / states_;
        log_emission[s] = static_cast<float>(std::log(std::max(b, kEmissionFloor)));
      }
    }
    similarity_.push_back(std::move(similarity));
    log_emission_.push_back(std::move(log_emission));
  }
  void DropOldest() override {
    similarity_.pop_front();
    log_emission_.pop_front();
  }
  void Clear() override {
    similarity_.clear();
    log_emission_.clear();
    positions_.clear();
    state_descriptors_.clear();
    state_norms_.clear();
  }

  std::vector<Assessment> Assess(const ViewIndexSnapshot& index,
                                 std::span<const QueryFrame> window) override {
    const std::size_t frames = window.size();
    const std::size_t objects = index.object_count();
    // The transitions depend only on the measured changes, the same for every object: kept
    // sparse, as (i, log a_ij) for the a_ij > 0 of each column j.
    std::vector<std::vector<std::vector<std::pair<int, double>>>> into(frames);
    for (std::size_t t = 1; t < frames; ++t) {
      const auto a = TransitionMatrix(sectors_, AzimuthChange(window[t - 1].azimuth, window[t].azimuth));
      into[t].resize(states_);
      for (int j = 0; j < states_; ++j) {
        for (int i = 0; i < states_; ++i) {
          if (a[i][j] > 0) into[t][j].emplace_back(i, std::log(a[i][j]));
        }
      }
    }
    paths_.assign(objects * frames, 0);
    std::vector<double> score(states_), next(states_);
    std::vector<int> back(frames * states_);
    std::vector<Assessment> assessments(objects);
    for (std::size_t o = 0; o < objects; ++o) {
      const std::size_t first = o * states_;
      for (int i = 0; i < states_; ++i) score[i] = log_initial_[i] + log_emission_[0][first + i];
      for (std::size_t t = 1; t < frames; ++t) {
        for (int j = 0; j < states_; ++j) {
          double best = kMinusInfinity;
          int arg = 0;
          for (const auto& [i, log_a] : into[t][j]) {
            if (score[i] + log_a > best) {
              best = score[i] + log_a;
              arg = i;
            }
          }
          next[j] = best + log_emission_[t][first + j];
          back[t * states_ + j] = arg;
        }
        score.swap(next);
      }
      int* path = &paths_[o * frames];
      path[frames - 1] = static_cast<int>(std::max_element(score.begin(), score.end()) - score.begin());
      for (std::size_t t = frames - 1; t > 0; --t) path[t - 1] = back[t * states_ + path[t]];
      double sum = 0;
      for (std::size_t t = 0; t < frames; ++t) sum += similarity_[t][first + path[t]];
      assessments[o].object = index.objects()[o].object;
      assessments[o].score = sum / static_cast<double>(frames);
    }
    return assessments;
  }

  void Complete(const ViewIndexSnapshot&, std::span<const QueryFrame> window,
                Assessment& assessment) override {
    const std::size_t o = positions_.at(assessment.object);
    const SectorViews& sectors = assessment.object->Sectors(states_);
    const auto& views = assessment.object->model().views;
    assessment.matched.clear();
    for (std::size_t t = 0; t < window.size(); ++t) {
      const int state = paths_[o * window.size() + t];
      MatchedView best{static_cast<int>(t), -1, -1};
      for (const int v : sectors.views[state]) {
        const double tc = Tanimoto(window[t].descriptor.values, views[v].descriptor);
        if (tc > best.similarity) best = {static_cast<int>(t), v, tc};
      }
      assessment.matched.push_back(best);
    }
    assessment.latest_azimuth = views[assessment.matched.back().view].azimuth;
  }

 private:
  // The state descriptors of every object of the snapshot, contiguous for the emission pass.
  void CacheStates(const ViewIndexSnapshot& index) {
    const auto& objects = index.objects();
    state_descriptors_.resize(objects.size() * states_ * kDescriptorSize);
    state_norms_.resize(objects.size() * states_);
    for (std::size_t o = 0; o < objects.size(); ++o) {
      positions_[objects[o].object] = o;
      const SectorViews& sectors = objects[o].object->Sectors(states_);
      for (int i = 0; i < states_; ++i) {
        const std::size_t s = o * states_ + i;
        std::copy(sectors.descriptor[i].begin(), sectors.descriptor[i].end(),
                  state_descriptors_.begin() + static_cast<std::ptrdiff_t>(s * kDescriptorSize));
        state_norms_[s] = sectors.squared_norm[i];
      }
    }
  }

  const int states_;
  const std::vector<Arc> sectors_;
  std::vector<double> log_initial_;
  std::unordered_map<const IndexedObject*, std::size_t> positions_;  // object -> position
  std::vector<float> state_descriptors_;  // [object][state][144]
  std::vector<double> state_norms_;       // [object][state]
  std::deque<std::vector<float>> similarity_;    // per window frame: TC(S_i, o_t), [object][state]
  std::deque<std::vector<float>> log_emission_;  // per window frame: log b_i(o_t)
  std::vector<int> paths_;                       // [object][frame]: last Assess's Viterbi paths
};

}  // namespace

std::unique_ptr<RecognitionEngine> MakeHmmEngine(const EngineOptions& options) {
  return std::make_unique<OrientationHmm>(options);
}

}  // namespace orbit
