#include "core/orientation_hmm.h"

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <deque>
#include <functional>
#include <limits>
#include <numeric>
#include <optional>
#include <span>
#include <stdexcept>

#include "core/cpu_dispatch.h"
#include "core/sector_similarity_table.h"
#include "core/similarity_rows.h"
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

SparseTransitions MakeSparseTransitions(std::span<const Arc> sectors, double delta) {
  const auto a = TransitionMatrix(sectors, delta);
  SparseTransitions step;
  step.into.resize(sectors.size());
  for (std::size_t j = 0; j < sectors.size(); ++j) {
    for (std::size_t i = 0; i < sectors.size(); ++i) {
      if (a[i][j] > 0) step.into[j].emplace_back(static_cast<int>(i), static_cast<float>(a[i][j]));
    }
  }
  return step;
}

SparseTransitions UnknownTurnTransitions(std::span<const Arc> sectors) {
  const std::vector<double> initial = InitialProbabilities(sectors);
  SparseTransitions step;
  step.into.resize(sectors.size());
  for (std::size_t j = 0; j < sectors.size(); ++j) {
    for (std::size_t i = 0; i < sectors.size(); ++i) {
      step.into[j].emplace_back(static_cast<int>(i), static_cast<float>(initial[j]));
    }
  }
  return step;
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

// In place, values[i * n + o] = TC(S_i, o_t) becomes b_i(o_t) up to a per-frame constant:
// the similarity floored at 1e-12 of the object's sum over its states, or 1 for every state when
// that sum is 0 (b uniform; unseen[o] = 1 then, else 0). best[o] is the object's highest
// emission, or 0 when it is unseen (its similarity on any path). `sum` is scratch of n floats.
ORBIT_AVX2_CLONES void EmissionsFromSimilarities(float* __restrict values, int states,
                                                 float* __restrict sum,
                                                 std::uint8_t* __restrict unseen,
                                                 float* __restrict best, std::size_t n) {
  for (std::size_t o = 0; o < n; ++o) sum[o] = 0.0f;
  for (int i = 0; i < states; ++i) {
    const float* row = &values[static_cast<std::size_t>(i) * n];
    for (std::size_t o = 0; o < n; ++o) sum[o] += row[o];
  }
  for (std::size_t o = 0; o < n; ++o) best[o] = 0.0f;
  for (int i = 0; i < states; ++i) {
    float* row = &values[static_cast<std::size_t>(i) * n];
    for (std::size_t o = 0; o < n; ++o) {
      const float floor = static_cast<float>(kEmissionFloor) * sum[o];
      row[o] = sum[o] > 0.0f ? std::max(row[o], floor) : 1.0f;
      best[o] = sum[o] > 0.0f ? std::max(best[o], row[o]) : 0.0f;
    }
  }
  for (std::size_t o = 0; o < n; ++o) unseen[o] = sum[o] > 0.0f ? 0 : 1;
}

// In place, values[k] = values[k]^(2^squarings) (EngineOptions::hmm_sharpness). At the 32nd
// power a similarity under about 0.065 underflows to 0: an object that matches a frame that
// poorly in every state gets an arbitrary path through it and reads 0 there, which changes
// nothing for the objects that can rank.
// Values that would fall below FLT_MIN are set to 0 at once: subnormal floats cost the
// multiplications here and in BatchViterbi tens of cycles each.
ORBIT_AVX2_CLONES void Sharpen(float* __restrict values, std::size_t count, int squarings) {
  if (squarings == 0) return;
  // The smallest value whose 2^squarings-th power is a normal float.
  const float smallest =
      std::pow(std::numeric_limits<float>::min(), 1.0f / static_cast<float>(1 << squarings));
  for (std::size_t k = 0; k < count; ++k) {
    float v = values[k] < smallest ? 0.0f : values[k];
    for (int s = 0; s < squarings; ++s) v *= v;
    values[k] = v;
  }
}

// out[o * rows + r] = in[r * columns + o]: a frame's [state][object] similarities stored object
// by object, so that decoding a few objects reads a few cache lines per frame.
void Transpose(const float* __restrict in, std::size_t rows, std::size_t columns,
               float* __restrict out) {
  for (std::size_t o = 0; o < columns; ++o) {
    for (std::size_t r = 0; r < rows; ++r) out[o * rows + r] = in[r * columns + o];
  }
}

// Rearranges `values`, `width` values per object for `before` objects, into the order of a
// snapshot of `after` objects described by `runs` (SnapshotChange::runs), in place; the added
// objects' values come from `added`. Kept runs moving towards the front go first, front to back,
// then those moving towards the back, back to front: since kept objects keep their relative
// order (a ViewIndex appends objects and merges segments oldest first), no run overwrites
// values still to be moved. Throws std::logic_error when they do not.
template <typename T>
void MoveRuns(std::span<const SnapshotChange::Run> runs, std::size_t before, std::size_t after,
              std::size_t width, const std::vector<T>& added, std::vector<T>& values) {
  std::size_t kept_end = 0;
  for (const SnapshotChange::Run& run : runs) {
    if (run.added) continue;
    if (run.source < kept_end) throw std::logic_error("MoveRuns: kept objects were reordered");
    kept_end = run.source + run.length;
  }
  if (after > before) values.resize(after * width);
  for (const SnapshotChange::Run& run : runs) {
    if (run.added || run.after >= run.source) continue;
    const auto from = values.begin() + static_cast<std::ptrdiff_t>(run.source * width);
    std::copy(from, from + static_cast<std::ptrdiff_t>(run.length * width),
              values.begin() + static_cast<std::ptrdiff_t>(run.after * width));
  }
  for (auto run = runs.rbegin(); run != runs.rend(); ++run) {
    if (run->added || run->after <= run->source) continue;
    const auto from = values.begin() + static_cast<std::ptrdiff_t>(run->source * width);
    const auto to_end =
        values.begin() + static_cast<std::ptrdiff_t>((run->after + run->length) * width);
    std::copy_backward(from, from + static_cast<std::ptrdiff_t>(run->length * width), to_end);
  }
  for (const SnapshotChange::Run& run : runs) {
    if (!run.added) continue;
    std::copy_n(added.begin() + static_cast<std::ptrdiff_t>(run.source * width), run.length * width,
                values.begin() + static_cast<std::ptrdiff_t>(run.after * width));
  }
  values.resize(after * width);
}

// The engine. Per frame (Append) it computes TC(S_i, o) for every state of every object at once
// (SectorSimilarityTable) and the emissions from them, and the sparse transitions from the
// previous frame; these stay with the frame while it is in the window. Per answer (Assess) it
// decodes the Viterbi paths of the objects that can rank over the window at once (BatchViterbi),
// in linear space: dividing b_i(o_t) = TC_i / sum_j TC_j by its per-frame constant changes no
// path's rank, so the raw similarities serve as emissions (with the same 1e-12 floor relative
// to the sum) and no logarithm is taken per state. A frame keeps only its emissions: the
// similarity of a state on an object's path is read back from them (TC = the emission, 0 for an object unseen in the
// frame; a floored TC reads 1e-12 of the sum too high, at most 8e-12), which halves what a
// session holds and streams through the caches per frame (8 frames x 8000 states x 4 bytes at
// 1000 objects).
class OrientationHmm final : public RecognitionEngine {
 public:
  explicit OrientationHmm(const EngineOptions& options)
      : RecognitionEngine("hmm", options),
        states_(options.hmm_states),
        sectors_(EqualSectors(states_)),
        unknown_turn_(UnknownTurnTransitions(sectors_)),
        viterbi_(InitialProbabilities(sectors_)) {}

 protected:
  void Append(const ViewIndexSnapshot& index, const QueryFrame& frame) override {
    if (!table_) table_ = SectorSimilarityTable::Of(index, states_);
    WindowFrame stored = std::move(spare_);
    Score(*table_, frame.descriptor.values, stored);
    if (previous_) {
      const std::optional<double> turn = MeasuredTurn(*previous_, frame);
      stored.step = turn ? MakeSparseTransitions(sectors_, *turn) : unknown_turn_;
    }
    previous_ = frame;
    frames_.push_back(std::move(stored));
  }
  void DropOldest() override {
    spare_ = std::move(frames_.front());  // its buffers serve the next frame
    frames_.pop_front();
  }
  void Clear() override {
    frames_.clear();
    previous_.reset();
    table_.reset();
  }

  // Objects kept move their columns to their new positions; objects added are scored against
  // the kept frames with a table of their own; removed ones are dropped. Each object's
  // similarities and emissions depend on that object alone, so the state equals a re-append.
  void Rebase(const ViewIndexSnapshot&, const ViewIndexSnapshot& after,
              const SnapshotChange& change, std::span<const QueryFrame> window) override {
    const std::size_t before_objects = table_->object_count();
    table_ = SectorSimilarityTable::Of(after, states_);
    const std::size_t objects = table_->object_count();

    std::vector<const IndexedObject*> added_objects;
    for (const ObjectSlot& slot : change.added) added_objects.push_back(slot.object);
    const SectorSimilarityTable added(added_objects, states_);

    // Each frame's arrays are rearranged in place, a block per run of kept objects, and the
    // added objects, scored now against the kept frames, copied in: an enrollment costs a
    // session the new object's similarities and a move of the objects after a deleted one,
    // not a copy of its whole window.
    const std::size_t states = static_cast<std::size_t>(states_);
    WindowFrame scored;
    for (std::size_t t = 0; t < frames_.size(); ++t) {
      WindowFrame& frame = frames_[t];
      if (!added_objects.empty()) Score(added, window[t].descriptor.values, scored);
      MoveRuns(change.runs, before_objects, objects, states, scored.emission, frame.emission);
      MoveRuns(change.runs, before_objects, objects, 1, scored.unseen, frame.unseen);
      MoveRuns(change.runs, before_objects, objects, 1, scored.best, frame.best);
    }
  }

  // Only the objects that can reach the ranking are decoded. An object's score averages the
  // emissions on its path, so it is at most the average of its best emission per frame
  // (WindowFrame::best): decoding the objects with the highest such bound until the next
  // bound is below the RankedDepth()-th score gives exactly the ranking, ties included, that
  // decoding every object gives. At 1000 objects that is a few dozen instead of 1000.
  std::vector<Assessment> Assess(const ViewIndexSnapshot& index,
                                 std::span<const QueryFrame> window) override {
    const std::size_t frames = window.size();
    const std::size_t objects = table_->object_count();
    if (objects == 0) return {};
    // Sums in double, frame by frame, as the scores are: a path's sum is then never above its
    // object's bound (every term is at most the frame's best, and rounding is monotone).
    std::vector<double> bound(objects, 0.0);
    for (std::size_t t = 0; t < frames; ++t) {
      const float* best = frames_[t].best.data();
      for (std::size_t o = 0; o < objects; ++o) bound[o] += best[o];
    }
    std::vector<std::uint32_t> order(objects);
    std::iota(order.begin(), order.end(), 0u);
    const auto higher_bound = [&](std::uint32_t a, std::uint32_t b) {
      return bound[a] > bound[b] || (bound[a] == bound[b] && a < b);
    };
    const std::size_t shown =
        std::min<std::size_t>(objects, static_cast<std::size_t>(RankedDepth(options())));
    // A first guess a little above the shown objects, doubled while an object left out could
    // still rank: every object decoded costs a cache line per frame when the session's window
    // is out of cache (starting at 32 instead: 8 closed-loop sessions at 1000 objects 7% fewer
    // frames/s, docs/results/load.md).
    std::size_t decoded = std::min(objects, std::max<std::size_t>(shown + 3, 8));
    std::vector<double> sums;
    for (;;) {
      std::nth_element(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(decoded) - 1,
                       order.end(), higher_bound);
      Decode(std::span(order).first(decoded), frames, sums);
      if (decoded == objects) break;
      std::vector<double> top(sums);
      std::nth_element(top.begin(), top.begin() + static_cast<std::ptrdiff_t>(shown) - 1,
                       top.end(), std::greater<>());
      const double least_shown = top[shown - 1];
      const double next_bound =
          bound[*std::min_element(order.begin() + static_cast<std::ptrdiff_t>(decoded),
                                  order.end(), higher_bound)];
      if (next_bound < least_shown) break;
      decoded = std::min(objects, 2 * decoded);
    }
    std::vector<Assessment> assessments(decoded);
    for (std::size_t j = 0; j < decoded; ++j) {
      assessments[j].object = index.objects()[order[j]].object;
      assessments[j].score = sums[j] / static_cast<double>(frames);
    }
    return assessments;
  }

  // The matched view of each frame is the most similar view of the path's sector there.
  void Complete(const ViewIndexSnapshot& index, std::span<const QueryFrame> window,
                const ObjectRows& rows, Assessment& assessment) override {
    const std::span<const std::uint16_t> path =
        viterbi_.path(static_cast<std::size_t>(lane_.at(index.PositionOf(assessment.object->id()))));
    const SectorViews& sectors = assessment.object->Sectors(states_);
    const auto& views = assessment.object->model().views;
    assessment.matched.clear();
    for (std::size_t t = 0; t < window.size(); ++t) {
      MatchedView best{static_cast<int>(t), -1, -1};
      for (const int v : sectors.views[path[t]]) {
        const double tc = rows.rows[t][v];
        if (tc > best.similarity) best = {static_cast<int>(t), v, tc};
      }
      assessment.matched.push_back(best);
    }
    assessment.latest_azimuth = views[assessment.matched.back().view].azimuth;
  }

 private:
  // What the engine keeps of a frame while it is in the window.
  struct WindowFrame {
    std::vector<float> emission;       // [object * states + state]: EmissionsFromSimilarities()
                                       // (Decode sharpens copies)
    std::vector<std::uint8_t> unseen;  // [object]: 1 when every state's TC is 0
    std::vector<float> best;           // [object]: its highest emission, 0 when unseen
    SparseTransitions step;         // from the previous frame (empty for the first)
  };

  // Decodes the objects at `positions` (lane j for positions[j]) over the window and sets
  // sums[j] to the sum of TC along object j's path; lane_ maps positions to lanes for Complete.
  void Decode(std::span<const std::uint32_t> positions, std::size_t frames,
              std::vector<double>& sums) {
    const std::size_t lanes = positions.size();
    lane_.assign(table_->object_count(), -1);
    for (std::size_t j = 0; j < lanes; ++j) lane_[positions[j]] = static_cast<std::int32_t>(j);
    // The decoded objects' emissions, gathered into BatchViterbi's [state][lane] layout and
    // sharpened as they are copied (the window keeps the similarities themselves). An object's
    // states are adjacent in a window frame, so a lane costs one cache line per frame.
    const std::size_t states = static_cast<std::size_t>(states_);
    const int sharpness = options().hmm_sharpness;
    gathered_.resize(frames);
    std::vector<const float*> emissions;
    std::vector<const SparseTransitions*> steps;
    for (std::size_t t = 0; t < frames; ++t) {
      const float* emission = frames_[t].emission.data();
      std::vector<float>& lanes_of_frame = gathered_[t];
      lanes_of_frame.resize(states * lanes);
      for (std::size_t j = 0; j < lanes; ++j) {
        const float* object_states = emission + positions[j] * states;
        for (std::size_t i = 0; i < states; ++i) lanes_of_frame[i * lanes + j] = object_states[i];
      }
      Sharpen(lanes_of_frame.data(), lanes_of_frame.size(), sharpness);
      emissions.push_back(lanes_of_frame.data());
      if (t > 0) steps.push_back(&frames_[t].step);
    }
    viterbi_.Decode(emissions, steps, lanes);
    sums.assign(lanes, 0.0);
    for (std::size_t j = 0; j < lanes; ++j) {
      const std::span<const std::uint16_t> path = viterbi_.path(j);
      for (std::size_t t = 0; t < frames; ++t) {
        // The TC of the path's state, from the window's own (unsharpened) array.
        if (!frames_[t].unseen[positions[j]]) {
          sums[j] += frames_[t].emission[positions[j] * states + path[t]];
        }
      }
    }
  }

  // The similarities and emissions of one frame for the objects of `table`: computed state by
  // state (the table's layout) in scratch, then stored object by object. The scratch is the
  // thread's, not the session's: a server thread serving many sessions in turn finds it in its
  // cache, where a session's own (36 KB at 1000 objects) would be a cold miss per line.
  void Score(const SectorSimilarityTable& table, const DescriptorValues& descriptor,
             WindowFrame& frame) {
    thread_local std::vector<float> by_state, sum;
    const std::size_t objects = table.object_count();
    const std::size_t states = static_cast<std::size_t>(states_);
    by_state.resize(objects * states);
    sum.resize(objects);
    frame.emission.resize(objects * states);
    frame.unseen.resize(objects);
    frame.best.resize(objects);
    table.Compute(descriptor, by_state);
    EmissionsFromSimilarities(by_state.data(), states_, sum.data(), frame.unseen.data(),
                              frame.best.data(), objects);
    Transpose(by_state.data(), states, objects, frame.emission.data());
  }

  const int states_;
  const std::vector<Arc> sectors_;
  const SparseTransitions unknown_turn_;  // the step to or from a frame without azimuth
  BatchViterbi viterbi_;  // holds the last Assess's paths, read by Complete
  std::shared_ptr<const SectorSimilarityTable> table_;  // the current snapshot's, shared
  std::deque<WindowFrame> frames_;
  std::optional<QueryFrame> previous_;  // the last frame appended, for the next turn
  std::vector<std::int32_t> lane_;                 // [object position]: its lane in viterbi_, or -1
  std::vector<std::vector<float>> gathered_;       // scratch: the decoded objects' emissions
  WindowFrame spare_;  // the last frame dropped: its buffers are reused by the next Append
};

}  // namespace

std::unique_ptr<RecognitionEngine> MakeHmmEngine(const EngineOptions& options) {
  return std::make_unique<OrientationHmm>(options);
}

}  // namespace orbit
