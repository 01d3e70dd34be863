#include "core/engines/orientation_hmm.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <functional>
#include <limits>
#include <numeric>
#include <optional>
#include <span>
#include <stdexcept>

#include "core/base/cpu_dispatch.h"
#include "core/descriptor/similarity.h"
#include "core/engines/candidate_hmm.h"
#include "core/engines/hmm_emissions.h"
#include "core/engines/hmm_session.h"
#include "core/engines/sector_similarity_table.h"
#include "core/engines/windowed_engine.h"
#include "core/index/similarity_rows.h"

namespace orbit {
namespace {

constexpr double kMinusInfinity = -std::numeric_limits<double>::infinity();

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

void MakeSparseTransitions(std::span<const Arc> sectors, double delta, SparseTransitions& step) {
  step.first.assign(1, 0);
  step.entries.clear();
  // TransitionMatrix()'s values, column by column, without the dense matrix.
  for (std::size_t j = 0; j < sectors.size(); ++j) {
    if (!(sectors[j].width > 0)) throw std::invalid_argument("an HMM sector has no width");
    const Arc shifted{sectors[j].start - WrapDegrees(delta), sectors[j].width};  // L_j
    for (std::size_t i = 0; i < sectors.size(); ++i) {
      const double a = ArcOverlap(shifted, sectors[i]) / shifted.width;
      if (a > 0) step.entries.emplace_back(static_cast<int>(i), static_cast<float>(a));
    }
    step.first.push_back(static_cast<std::uint32_t>(step.entries.size()));
  }
}

SparseTransitions MakeSparseTransitions(std::span<const Arc> sectors, double delta) {
  SparseTransitions step;
  MakeSparseTransitions(sectors, delta, step);
  return step;
}

SparseTransitions UnknownTurnTransitions(std::span<const Arc> sectors) {
  const std::vector<double> initial = InitialProbabilities(sectors);
  SparseTransitions step;
  step.first.assign(1, 0);
  for (std::size_t j = 0; j < sectors.size(); ++j) {
    for (std::size_t i = 0; i < sectors.size(); ++i) {
      step.entries.emplace_back(static_cast<int>(i), static_cast<float>(initial[j]));
    }
    step.first.push_back(static_cast<std::uint32_t>(step.entries.size()));
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

// Sets top[0 .. count) to the positions of the `count` highest bounds, ties to the lower
// position, so that top[count - 1] is the lowest of them. A few (the usual case) are kept
// sorted as one pass meets them, which costs a comparison per object that rarely succeeds;
// many are selected with std::nth_element.
void HighestBounds(std::span<const std::uint32_t> bound, std::size_t count,
                   std::vector<std::uint32_t>& top) {
  // Higher key, higher rank: the bound, then the lower position.
  const auto key = [&](std::uint32_t o) {
    return static_cast<std::uint64_t>(bound[o]) << 32 | (0xFFFFFFFFu - o);
  };
  top.clear();
  if (count > 64) {
    top.resize(bound.size());
    std::iota(top.begin(), top.end(), 0u);
    std::nth_element(top.begin(), top.begin() + static_cast<std::ptrdiff_t>(count) - 1, top.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return key(a) > key(b); });
    top.resize(count);
    return;
  }
  for (std::uint32_t o = 0; o < bound.size(); ++o) {
    const std::uint64_t k = key(o);
    if (top.size() == count && k <= key(top.back())) continue;
    if (top.size() == count) top.pop_back();
    auto at = top.end();
    while (at != top.begin() && key(*(at - 1)) < k) --at;
    top.insert(at, o);
  }
}

// kept += all[i * objects + o] for each object o of `positions`, state by state: their emissions,
// object by object, from a frame's [state][object] array.
void AppendEmissions(std::span<const float> all, std::size_t objects, int states,
                     std::span<const std::uint32_t> positions, std::vector<float>& kept) {
  for (const std::uint32_t position : positions) {
    for (std::size_t i = 0; i < static_cast<std::size_t>(states); ++i) {
      kept.push_back(all[i * objects + position]);
    }
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
// previous frame. Per answer (Assess) it decodes the Viterbi paths of the objects that can rank
// over the window at once (BatchViterbi), in linear space: dividing b_i(o_t) = TC_i / sum_j TC_j
// by its per-frame constant changes no path's rank, so the raw similarities serve as emissions
// (with the same 1e-12 floor relative to the sum) and no logarithm is taken per state. The
// similarity of a state on an object's path is read back from its emission (TC = the emission,
// 0 for an object unseen in the frame; a floored TC reads 1e-12 of the sum too high, at most
// 8e-12).
//
// What a frame keeps while it is in the window: every object's best emission in 16 bits (the
// bound that chooses what to decode), and the emissions of the few objects decoded lately ("kept"
// objects), not all 8000 states' (32 KB a frame, 256 KB a session at 1000 objects). A session
// then holds far less, so that many more sessions' windows stay in the
// shared cache, where whole windows streamed from memory on every frame (docs/results/load.md,
// "A window of bounds"). An object decoded for the first time gets its emissions for the older
// frames from its own sector sums (SectorSimilarityTable::ComputeObject: the same values to the
// last bit).
class OrientationHmm final : public HmmSession {
 public:
  explicit OrientationHmm(const EngineOptions& options) : HmmSession(options) {}

 protected:
  void Append(const ViewIndexSnapshot& index, const QueryFrame& frame) override {
    if (!table_) {
      table_ = SectorSimilarityTable::Of(index, states_);
      ForgetKept();
    }
    WindowFrame stored = std::move(spare_);
    const std::span<const float> emissions =
        Score(*table_, frame.descriptor.values, states_, stored.best);
    const std::size_t objects = table_->object_count();
    stored.kept.clear();
    AppendEmissions(emissions, objects, states_, kept_, stored.kept);
    StepTo(frame, stored.step);
    bound_.resize(objects, 0);
    RunHotLoop<AddBounds>(stored.best.data(), false, bound_.data(), objects);
    frames_.push_back(std::move(stored));
  }
  void DropOldest() override {
    RunHotLoop<AddBounds>(frames_.front().best.data(), true, bound_.data(), bound_.size());
    spare_ = std::move(frames_.front());  // its buffers serve the next frame
    frames_.pop_front();
  }
  void Clear() override {
    frames_.clear();
    bound_.clear();
    ForgetSteps();
    table_.reset();
    ForgetKept();
  }

  // Objects kept move their bounds to their new positions; objects added are scored against
  // the kept frames with a table of their own; removed ones are dropped. Each object's
  // similarities and emissions depend on that object alone, so the state equals a re-append.
  // The kept objects' emissions are dropped: the next answer reads the ones it decodes back.
  void Rebase(const ViewIndexSnapshot&, const ViewIndexSnapshot& after,
              const SnapshotChange& change, std::span<const QueryFrame> window) override {
    const std::size_t before_objects = table_->object_count();
    table_ = SectorSimilarityTable::Of(after, states_);
    const std::size_t objects = table_->object_count();

    std::vector<const IndexedObject*> added_objects;
    for (const ObjectSlot& slot : change.added) added_objects.push_back(slot.object);
    const SectorSimilarityTable added(added_objects, states_);

    // Each frame's bounds are rearranged in place, a block per run of kept objects, and the
    // added objects', scored now against the kept frames, copied in: an enrollment costs a
    // session the new object's similarities, not a copy of its whole window.
    std::vector<std::uint16_t> added_best;
    for (std::size_t t = 0; t < frames_.size(); ++t) {
      if (!added_objects.empty()) Score(added, window[t].descriptor.values, states_, added_best);
      MoveRuns(change.runs, before_objects, objects, 1, added_best, frames_[t].best);
    }
    bound_.assign(objects, 0);
    for (const WindowFrame& frame : frames_) {
      RunHotLoop<AddBounds>(frame.best.data(), false, bound_.data(), objects);
    }
    ForgetKept();
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
    // bound_ is in integer units (exact): a path's sum of similarities is never above its
    // object's bound, as every term is at most the frame's best and the units round up.
    const std::size_t shown =
        std::min<std::size_t>(objects, static_cast<std::size_t>(RankedDepth(options())));
    // A first guess a little above the shown objects, doubled while an object left out could
    // still rank: every object decoded costs a cache line per frame when the session's window
    // is out of cache (starting at 32 instead gave closed-loop sessions fewer frames/s:
    // docs/results/load.md, "At 1000 objects with the product default, again"). top[decoded] is
    // the best object left out.
    std::size_t decoded = std::min(objects, std::max<std::size_t>(shown + 3, 8));
    thread_local std::vector<std::uint32_t> top;  // the thread's: warm whichever session it serves
    std::vector<double> sums;
    for (;;) {
      HighestBounds(bound_, std::min(objects, decoded + 1), top);
      Decode(index, window, std::span(top).first(decoded), sums);
      if (decoded == objects) break;
      std::vector<double> highest(sums);
      std::nth_element(highest.begin(), highest.begin() + static_cast<std::ptrdiff_t>(shown) - 1,
                       highest.end(), std::greater<>());
      const double least_shown = highest[shown - 1];
      // Exact: units / 2^15.
      const double next_bound = bound_[top[decoded]] / static_cast<double>(kBoundUnitsPerOne);
      if (next_bound < least_shown) break;
      decoded = std::min(objects, 2 * decoded);
    }
    if (kept_.size() > std::max(kKeptObjects, decoded)) KeepOnly(std::span(top).first(decoded));
    std::vector<Assessment> assessments(decoded);
    for (std::size_t j = 0; j < decoded; ++j) {
      assessments[j].object = index.objects()[top[j]].object;
      assessments[j].score = sums[j] / static_cast<double>(frames);
    }
    return assessments;
  }

  // The matched view of each frame is the most similar view of the path's sector there.
  void Complete(const ViewIndexSnapshot& index, std::span<const QueryFrame> window,
                const ObjectRows& rows, Assessment& assessment) override {
    const auto position = static_cast<std::uint32_t>(index.PositionOf(assessment.object->id()));
    const auto lane = std::find(lanes_.begin(), lanes_.end(), position);
    if (lane == lanes_.end()) {
      throw std::logic_error("HMM: an object the last answer did not decode");
    }
    CompletePath(static_cast<std::size_t>(lane - lanes_.begin()), window, rows, assessment);
  }

 private:
  // When more objects than this (and than the last answer decoded) are kept, all but the last
  // answer's are dropped. A kept object costs `states` values per frame; an object decoded
  // again after being dropped costs its sector sums' products with each older frame. (32
  // instead made no session faster: docs/results/load.md, "Cold reads and the floor".)
  static constexpr std::size_t kKeptObjects = 128;

  // What the engine keeps of a frame while it is in the window.
  struct WindowFrame {
    std::vector<std::uint16_t> best;  // [object]: its highest emission in BoundUnits(), 0 when
                                      // unseen (every TC 0), > 0 when seen
    std::vector<float> kept;          // [slot * states + state]: the emissions of kept_[slot]
    SparseTransitions step;           // from the previous frame (empty for the first)
  };

  // The emissions of one frame for every object of `table`, [state * objects + object] in the
  // thread's scratch (valid until the thread's next Score), and best[object] (BoundUnits). The
  // scratch is the thread's, not the session's: a server thread serving many sessions in turn
  // finds it in its cache, where a session's own (32 KB at 1000 objects) would be a cold miss
  // per line.
  static std::span<const float> Score(const SectorSimilarityTable& table,
                                      const DescriptorValues& descriptor, int states,
                                      std::vector<std::uint16_t>& best) {
    thread_local std::vector<float> by_state, sum, best_emission;
    const std::size_t objects = table.object_count();
    by_state.resize(objects * static_cast<std::size_t>(states));
    sum.resize(objects);
    best_emission.resize(objects);
    best.resize(objects);
    table.Compute(descriptor, by_state);
    RunHotLoop<EmissionsFromSimilarities>(by_state.data(), states, sum.data(), best_emission.data(),
                                          objects);
    RunHotLoop<BoundUnits>(best_emission.data(), best.data(), objects);
    return by_state;
  }

  void ForgetKept() {
    kept_.clear();
    slot_.assign(table_ ? table_->object_count() : 0, -1);
    for (WindowFrame& frame : frames_) frame.kept.clear();
  }

  // Makes the objects at `positions` kept, with their emissions in every window frame, read
  // back object by object from their sector sums, or from the whole frame's table when more
  // than an eighth of the objects are new to it (a frame that many objects match equally, or
  // the first answer after a model change), which then costs less. Objects already kept stay.
  void Keep(const ViewIndexSnapshot& index, std::span<const QueryFrame> window,
            std::span<const std::uint32_t> positions) {
    std::vector<std::uint32_t> added;
    for (const std::uint32_t position : positions) {
      if (slot_[position] >= 0) continue;
      slot_[position] = static_cast<std::int32_t>(kept_.size());
      kept_.push_back(position);
      added.push_back(position);
    }
    if (added.empty()) return;
    const std::size_t states = static_cast<std::size_t>(states_);
    const std::size_t objects = table_->object_count();
    const bool whole_frames = added.size() * 8 > objects;
    std::vector<float> emissions(states);
    std::vector<std::uint16_t> bests;
    std::vector<const SectorViews*> sectors;
    for (const std::uint32_t position : added) {
      if (!whole_frames) sectors.push_back(&index.objects()[position].object->Sectors(states_));
    }
    float sum = 0, best = 0;
    for (std::size_t t = 0; t < frames_.size(); ++t) {
      std::vector<float>& kept = frames_[t].kept;
      if (whole_frames) {
        AppendEmissions(Score(*table_, window[t].descriptor.values, states_, bests), objects,
                        states_, added, kept);
        continue;
      }
      for (const SectorViews* object_sectors : sectors) {
        SectorSimilarityTable::ComputeObject(window[t].descriptor.values, *object_sectors,
                                             emissions);
        RunHotLoop<EmissionsFromSimilarities>(emissions.data(), states_, &sum, &best, 1);
        kept.insert(kept.end(), emissions.begin(), emissions.end());
      }
    }
  }

  // Keeps the objects at `positions` only, in this order.
  void KeepOnly(std::span<const std::uint32_t> positions) {
    const std::size_t states = static_cast<std::size_t>(states_);
    std::vector<float> kept;
    for (WindowFrame& frame : frames_) {
      kept.clear();
      for (const std::uint32_t position : positions) {
        const auto from =
            frame.kept.begin() + slot_[position] * static_cast<std::ptrdiff_t>(states);
        kept.insert(kept.end(), from, from + static_cast<std::ptrdiff_t>(states));
      }
      frame.kept.swap(kept);
    }
    for (const std::uint32_t position : kept_) slot_[position] = -1;
    kept_.assign(positions.begin(), positions.end());
    for (std::size_t slot = 0; slot < kept_.size(); ++slot) {
      slot_[kept_[slot]] = static_cast<std::int32_t>(slot);
    }
  }

  // Asks for every line the decoding of `positions` reads from the window at once: the kept
  // emissions of each object in each frame and each frame's transitions. Where the session's
  // window is out of cache (hundreds of sessions), the gathering below would otherwise wait for
  // them a frame at a time, behind the previous frame's sharpening (docs/results/load.md, "Cold
  // reads and the floor", measures the gain).
  void PrefetchDecoded(std::span<const std::uint32_t> positions) const {
    constexpr std::size_t kEntriesPerLine = 64 / sizeof(std::pair<int, float>);
    const std::size_t states = static_cast<std::size_t>(states_);
    for (const WindowFrame& frame : frames_) {
      for (const std::uint32_t position : positions) {
        const float* emissions = &frame.kept[static_cast<std::size_t>(slot_[position]) * states];
        __builtin_prefetch(emissions);
        __builtin_prefetch(emissions + states - 1);
      }
      __builtin_prefetch(frame.step.first.data());
      for (std::size_t e = 0; e < frame.step.entries.size(); e += kEntriesPerLine) {
        __builtin_prefetch(&frame.step.entries[e]);
      }
    }
  }

  // Decodes the objects at `positions` (lane j for positions[j]) over the window and sets
  // sums[j] to the sum of TC along object j's path; lanes_ keeps the positions for Complete.
  void Decode(const ViewIndexSnapshot& index, std::span<const QueryFrame> window,
              std::span<const std::uint32_t> positions, std::vector<double>& sums) {
    Keep(index, window, positions);
    const std::size_t frames = frames_.size();
    const std::size_t lanes = positions.size();
    lanes_.assign(positions.begin(), positions.end());
    // A kept object's states are adjacent in a window frame.
    const std::size_t states = static_cast<std::size_t>(states_);
    PrefetchDecoded(positions);
    std::vector<const float*> kept(frames * lanes);
    std::vector<const SparseTransitions*> steps;
    for (std::size_t t = 0; t < frames; ++t) {
      for (std::size_t j = 0; j < lanes; ++j) {
        kept[t * lanes + j] =
            &frames_[t].kept[static_cast<std::size_t>(slot_[positions[j]]) * states];
      }
      if (t > 0) steps.push_back(&frames_[t].step);
    }
    DecodeKept(kept, frames, lanes, steps, sums);
  }

  std::shared_ptr<const SectorSimilarityTable> table_;  // the current snapshot's, shared
  std::deque<WindowFrame> frames_;
  std::vector<std::uint32_t> bound_;  // [object]: the sum of its best over the window frames
  std::vector<std::uint32_t> kept_;   // [slot]: the position of a kept object
  std::vector<std::int32_t> slot_;    // [object position]: its slot in kept_, or -1
  std::vector<std::uint32_t> lanes_;  // [lane of the last decoding]: the object position there
  WindowFrame spare_;  // the last frame dropped: its buffers are reused by the next Append
};

}  // namespace

std::unique_ptr<RecognitionEngine> MakeHmmEngine(const EngineOptions& options) {
  if (options.candidate_objects > 0) {
    return MakeCandidateHmmEngine(options, std::make_unique<OrientationHmm>(options));
  }
  return std::make_unique<OrientationHmm>(options);
}

}  // namespace orbit
