#include "core/orientation_hmm.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <deque>
#include <limits>
#include <stdexcept>
#include <unordered_map>

#include <emmintrin.h>  // SSE2: part of every x86-64 CPU

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

// Sector sums are exact in 16 bits while a sector holds at most this many views (7 each).
constexpr int kMaxViewsForExactSums = 32767 / kDescriptorMaxValue;

// q.s over 144 16-bit values, exact: |q_i s_i| <= 7 * 32767 and eight such products per lane
// stay far below 2^31.
std::int32_t Dot(const std::int16_t* q, const std::int16_t* s) {
  __m128i sum = _mm_setzero_si128();
  for (int i = 0; i < kDescriptorSize; i += 8) {
    sum = _mm_add_epi32(sum, _mm_madd_epi16(_mm_loadu_si128(reinterpret_cast<const __m128i*>(q + i)),
                                            _mm_loadu_si128(reinterpret_cast<const __m128i*>(s + i))));
  }
  sum = _mm_add_epi32(sum, _mm_shuffle_epi32(sum, _MM_SHUFFLE(1, 0, 3, 2)));
  sum = _mm_add_epi32(sum, _mm_shuffle_epi32(sum, _MM_SHUFFLE(2, 3, 0, 1)));
  return _mm_cvtsi128_si32(sum);
}

// The engine. Per frame it computes TC(S_i, o) for every state of every object, exactly and
// cheaply: a state descriptor is the mean of some views, so S_i . o = (sum of those views) . o /
// count, an integer dot product with the sector's sum. Viterbi then runs in linear space with
// per-frame rescaling: dividing b_i(o_t) = TC_i / sum_j TC_j by its per-frame constant changes
// no path's rank, so the raw similarities serve as emissions (with the same 1e-12 floor relative
// to the sum) and no logarithm is taken per state.
class OrientationHmm final : public RecognitionEngine {
 public:
  explicit OrientationHmm(const EngineOptions& options)
      : RecognitionEngine("hmm", options),
        states_(options.hmm_states),
        sectors_(EqualSectors(states_)),
        initial_(InitialProbabilities(sectors_)) {}

 protected:
  void Append(const ViewIndexSnapshot& index, const QueryFrame& frame) override {
    if (positions_.empty() && index.object_count() > 0) CacheStates(index);
    const std::size_t objects = index.object_count();
    alignas(16) std::int16_t query[kDescriptorSize];
    std::int32_t query_norm = 0;
    for (int d = 0; d < kDescriptorSize; ++d) {
      query[d] = frame.descriptor.values[d];
      query_norm += query[d] * query[d];
    }
    std::vector<float> similarity(objects * states_);
    for (std::size_t s = 0; s < objects * states_; ++s) {
      double tc;
      if (!exact_sums_[s]) {
        tc = Tanimoto(frame.descriptor.values, *state_means_[s]);
      } else if (query_norm == 0 && state_norms_[s] == 0) {
        tc = 1.0;
      } else {
        const double qc = Dot(query, &state_sums_[s * kDescriptorSize]) / state_counts_[s];
        const double denominator = query_norm + state_norms_[s] - qc;
        tc = denominator > 0 ? qc / denominator : 0.0;
      }
      similarity[s] = static_cast<float>(tc);
    }
    std::vector<float> emission(objects * states_);
    for (std::size_t o = 0; o < objects; ++o) {
      Emission(&similarity[o * states_], &emission[o * states_]);
    }
    similarity_.push_back(std::move(similarity));
    emission_.push_back(std::move(emission));
  }
  void DropOldest() override {
    similarity_.pop_front();
    emission_.pop_front();
  }
  void Clear() override {
    similarity_.clear();
    emission_.clear();
    positions_.clear();
    state_sums_.clear();
    state_counts_.clear();
    state_norms_.clear();
    state_means_.clear();
    exact_sums_.clear();
  }

  std::vector<Assessment> Assess(const ViewIndexSnapshot& index,
                                 std::span<const QueryFrame> window) override {
    const std::size_t frames = window.size();
    const std::size_t objects = index.object_count();
    // The transitions depend only on the measured changes, the same for every object: kept
    // sparse, as (i, a_ij) for the a_ij > 0 of each column j.
    std::vector<std::vector<std::vector<std::pair<int, double>>>> into(frames);
    for (std::size_t t = 1; t < frames; ++t) {
      const auto a =
          TransitionMatrix(sectors_, AzimuthChange(window[t - 1].azimuth, window[t].azimuth));
      into[t].resize(states_);
      for (int j = 0; j < states_; ++j) {
        for (int i = 0; i < states_; ++i) {
          if (a[i][j] > 0) into[t][j].emplace_back(i, a[i][j]);
        }
      }
    }
    paths_.assign(objects * frames, 0);
    std::vector<double> score(states_), next(states_);
    std::vector<int> back(frames * states_);
    std::vector<Assessment> assessments(objects);
    for (std::size_t o = 0; o < objects; ++o) {
      const std::size_t first = o * states_;
      for (std::size_t t = 0; t < frames; ++t) {
        const float* emission = &emission_[t][first];
        if (t == 0) {
          for (int i = 0; i < states_; ++i) score[i] = initial_[i] * emission[i];
        } else {
          for (int j = 0; j < states_; ++j) {
            double best = 0;
            int arg = into[t][j].front().first;
            for (const auto& [i, a] : into[t][j]) {
              if (score[i] * a > best) {
                best = score[i] * a;
                arg = i;
              }
            }
            next[j] = best * emission[j];
            back[t * states_ + j] = arg;
          }
          score.swap(next);
        }
        // Rescale so that long windows never underflow; ranks are unchanged.
        const double top = *std::max_element(score.begin(), score.end());
        if (top > 0) {
          const double scale = 1.0 / top;
          for (double& value : score) value *= scale;
        }
      }
      int* path = &paths_[o * frames];
      path[frames - 1] =
          static_cast<int>(std::max_element(score.begin(), score.end()) - score.begin());
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
  // Emissions up to a per-frame constant: TC_i floored at 1e-12 of the sum, or all 1 when every
  // TC is 0 (b uniform).
  void Emission(const float* similarity, float* emission) const {
    double sum = 0;
    for (int i = 0; i < states_; ++i) sum += similarity[i];
    for (int i = 0; i < states_; ++i) {
      emission[i] = static_cast<float>(
          sum > 0 ? std::max<double>(similarity[i], kEmissionFloor * sum) : 1.0);
    }
  }

  // The sector sums of every object of the snapshot, contiguous for the emission pass.
  void CacheStates(const ViewIndexSnapshot& index) {
    const auto& objects = index.objects();
    const std::size_t states = objects.size() * states_;
    state_sums_.assign(states * kDescriptorSize, 0);
    state_counts_.resize(states);
    state_norms_.resize(states);
    state_means_.resize(states);
    exact_sums_.resize(states);
    for (std::size_t o = 0; o < objects.size(); ++o) {
      positions_[objects[o].object] = o;
      const SectorViews& sectors = objects[o].object->Sectors(states_);
      for (int i = 0; i < states_; ++i) {
        const std::size_t s = o * states_ + i;
        const std::vector<int>& members = sectors.views[i];
        state_counts_[s] = static_cast<double>(members.size());
        state_means_[s] = &sectors.descriptor[i];
        exact_sums_[s] = members.size() <= static_cast<std::size_t>(kMaxViewsForExactSums);
        std::array<double, kDescriptorSize> sum{};
        for (const int v : members) {
          const DescriptorValues& values = objects[o].object->model().views[v].descriptor;
          for (int d = 0; d < kDescriptorSize; ++d) sum[d] += values[d];
        }
        double norm = 0;
        for (int d = 0; d < kDescriptorSize; ++d) {
          const double mean = sum[d] / state_counts_[s];
          norm += mean * mean;
          if (exact_sums_[s]) state_sums_[s * kDescriptorSize + d] = static_cast<std::int16_t>(sum[d]);
        }
        state_norms_[s] = norm;
      }
    }
  }

  const int states_;
  const std::vector<Arc> sectors_;
  const std::vector<double> initial_;
  std::unordered_map<const IndexedObject*, std::size_t> positions_;  // object -> position
  // Per state of every object ([object][state]): the sum of its views, their count, the
  // squared norm of their mean, the mean itself (for sectors too large for 16-bit sums).
  std::vector<std::int16_t> state_sums_;  // [object][state][144]
  std::vector<double> state_counts_;
  std::vector<double> state_norms_;
  std::vector<const MeanDescriptor*> state_means_;
  std::vector<char> exact_sums_;
  std::deque<std::vector<float>> similarity_;  // per window frame: TC(S_i, o_t), [object][state]
  std::deque<std::vector<float>> emission_;    // per window frame: Emission(), [object][state]
  std::vector<int> paths_;                     // [object][frame]: last Assess's Viterbi paths
};

}  // namespace

std::unique_ptr<RecognitionEngine> MakeHmmEngine(const EngineOptions& options) {
  return std::make_unique<OrientationHmm>(options);
}

}  // namespace orbit
