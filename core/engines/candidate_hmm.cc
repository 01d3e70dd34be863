#include "core/engines/candidate_hmm.h"

#include <algorithm>
#include <cstdint>
#include <deque>
#include <optional>
#include <span>
#include <stdexcept>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/base/cpu_dispatch.h"
#include "core/engines/batch_viterbi.h"
#include "core/engines/hmm_emissions.h"
#include "core/engines/hmm_session.h"
#include "core/engines/orientation_hmm.h"
#include "core/engines/sector_similarity_table.h"
#include "core/engines/windowed_engine.h"
#include "core/index/similarity_rows.h"

namespace orbit {
namespace {

// The fewest objects a frame asks the index for: enough for the ranking and its runner-up.
constexpr int kFewestCandidates = 8;

// The most candidates an answer decodes in one pass before it prunes by bound.
constexpr std::size_t kDecodedAtOnce = 64;

// The HMM over candidates. Per frame (Append) it asks the index for candidates, computes their
// emissions from their own sector sums (SectorSimilarityTable::ComputeObject, as the HMM over
// every object reads back the objects it decodes) and tallies each candidate's best emission in
// the window. An object not proposed in a frame is bounded there by the lowest proposed
// object's summary similarity (the frame's floor): its bound is its tally plus the floors of
// the frames that did not propose it. Per answer (Assess) it decodes the window's candidates in
// order of bound, as the HMM over every object does, until no candidate left out can rank.
class CandidateHmm final : public HmmSession {
 public:
  explicit CandidateHmm(const EngineOptions& options) : HmmSession(options) {}

 protected:
  void Append(const ViewIndexSnapshot& index, const QueryFrame& frame) override {
    const int wanted = std::max(options().candidate_objects, kFewestCandidates);
    const std::vector<ObjectCandidate> candidates =
        index.ObjectCandidates(frame.descriptor.values, wanted);
    WindowFrame stored(frame.descriptor.values);
    // Objects not proposed are bounded by the lowest proposed summary; none is left out when
    // every object was proposed.
    if (candidates.size() < index.object_count() && !candidates.empty()) {
      stored.floor =
          static_cast<std::uint16_t>(std::ceil(candidates.back().similarity * kBoundUnitsPerOne));
    }
    for (const ObjectCandidate& candidate : candidates) {
      AddEmissions(*index.objects()[candidate.position].object, stored);
      Count(stored.entries.back(), stored);
    }
    stored.Sort();
    floors_ += stored.floor;
    StepTo(frame, stored.step);
    frames_.push_back(std::move(stored));
  }

  void DropOldest() override {
    const WindowFrame& oldest = frames_.front();
    for (const Entry& entry : oldest.entries) {
      if (entry.candidate) Uncount(entry, oldest);
    }
    floors_ -= oldest.floor;
    frames_.pop_front();
  }

  // Keeps what the window's frames proposed across a change of the model set
  // (docs/design.md#object-candidates): a removed object (deleted, or replaced by a new version)
  // leaves every frame; an added one joins each frame that would have proposed it, its best
  // emission there at least the frame's floor (every frame that proposed every object); the
  // kept objects' emissions and the frames' transitions stay. An enrollment then costs a
  // session the new object's emissions in each window frame instead of a search of the index
  // per frame, which hundreds of sessions would all run within a few frames of the change.
  void Rebase(const ViewIndexSnapshot&, const ViewIndexSnapshot&, const SnapshotChange& change,
              std::span<const QueryFrame>) override {
    std::vector<const IndexedObject*> removed(change.removed);
    std::sort(removed.begin(), removed.end());
    for (WindowFrame& frame : frames_) {
      // A removed object's emissions stay in the frame's buffer, unreferenced, until the frame
      // leaves the window: its entry's offset is all that finds them.
      std::erase_if(frame.entries, [&](const Entry& entry) {
        if (!std::binary_search(removed.begin(), removed.end(), entry.object)) return false;
        if (entry.candidate) Uncount(entry, frame);
        return true;
      });
      for (const ObjectSlot& slot : change.added) {
        AddEmissions(*slot.object, frame);
        if (frame.best.back() >= frame.floor) {
          Count(frame.entries.back(), frame);
        } else {
          frame.entries.pop_back();
          frame.best.pop_back();
          frame.emissions.resize(frame.emissions.size() - static_cast<std::size_t>(states_));
        }
      }
      frame.Sort();
    }
    lanes_.clear();
  }

  void Clear() override {
    frames_.clear();
    tallies_.clear();
    floors_ = 0;
    ForgetSteps();
  }

  std::vector<Assessment> Assess(const ViewIndexSnapshot& index,
                                 std::span<const QueryFrame> window) override {
    if (tallies_.empty()) return {};
    // The window's candidates, highest bound first (ties: lower id).
    std::vector<std::pair<std::uint32_t, const IndexedObject*>> bounds;
    bounds.reserve(tallies_.size());
    for (const auto& [object, tally] : tallies_) {
      bounds.emplace_back(tally.units + (floors_ - tally.floors), object);
    }
    std::sort(bounds.begin(), bounds.end(), [](const auto& a, const auto& b) {
      return a.first > b.first || (a.first == b.first && a.second->id() < b.second->id());
    });
    const std::size_t objects = bounds.size();
    const std::size_t shown =
        std::min<std::size_t>(objects, static_cast<std::size_t>(RankedDepth(options())));
    // The window's candidates sit close to its floors, so their bounds seldom stop the doubling
    // before it reaches them all (docs/design.md#object-candidates): up to kDecodedAtOnce of them
    // are decoded in one pass rather than in rounds of 8, 16, 32, ...
    std::size_t decoded =
        objects <= kDecodedAtOnce
            ? objects
            : std::min(objects, std::max<std::size_t>(shown + 3, kFewestCandidates));
    std::vector<double> sums;
    std::vector<const IndexedObject*> chosen;
    for (;;) {
      chosen.clear();
      for (std::size_t j = 0; j < decoded; ++j) chosen.push_back(bounds[j].second);
      Decode(chosen, sums);
      if (decoded == objects) break;
      std::vector<double> highest(sums);
      std::nth_element(highest.begin(), highest.begin() + static_cast<std::ptrdiff_t>(shown) - 1,
                       highest.end(), std::greater<>());
      const double least_shown = highest[shown - 1];
      if (bounds[decoded].first / static_cast<double>(kBoundUnitsPerOne) < least_shown) break;
      decoded = std::min(objects, 2 * decoded);
    }
    static_cast<void>(index);
    std::vector<Assessment> assessments(decoded);
    for (std::size_t j = 0; j < decoded; ++j) {
      assessments[j].object = chosen[j];
      assessments[j].score = sums[j] / static_cast<double>(window.size());
    }
    return assessments;
  }

  // The matched view of each frame is the most similar view of the path's sector there.
  void Complete(const ViewIndexSnapshot&, std::span<const QueryFrame> window,
                const ObjectRows& rows, Assessment& assessment) override {
    const auto lane = std::find(lanes_.begin(), lanes_.end(), assessment.object);
    if (lane == lanes_.end()) {
      throw std::logic_error("HMM: an object the last answer did not decode");
    }
    CompletePath(static_cast<std::size_t>(lane - lanes_.begin()), window, rows, assessment);
  }

 private:
  // An object's emissions in one frame: emissions[offset, offset + states).
  struct Entry {
    const IndexedObject* object = nullptr;
    std::uint32_t offset = 0;
    bool candidate = false;  // proposed by the index for this frame (counts in its tally)
  };

  // What the engine keeps of a frame while it is in the window.
  struct WindowFrame {
    explicit WindowFrame(const DescriptorValues& values) : query(values) {}

    QueryBins query;             // the frame's descriptor
    std::vector<Entry> entries;  // sorted by object
    std::vector<float> emissions;
    std::vector<std::uint16_t> best;  // [offset / states]: the entry's best emission, BoundUnits
    std::uint16_t floor = 0;          // the bound of an object not proposed, BoundUnits
    SparseTransitions step;           // from the previous frame (empty for the first)

    void Sort() {
      std::sort(entries.begin(), entries.end(),
                [](const Entry& a, const Entry& b) { return a.object < b.object; });
    }
    const Entry* Find(const IndexedObject* object) const {
      const auto at = std::lower_bound(
          entries.begin(), entries.end(), object,
          [](const Entry& entry, const IndexedObject* o) { return entry.object < o; });
      return at != entries.end() && at->object == object ? &*at : nullptr;
    }
  };

  // A candidate's sum over the window: its best emissions in the frames that proposed it, in
  // BoundUnits, those frames' floors, and how many they are.
  struct Tally {
    std::uint32_t units = 0;
    std::uint32_t floors = 0;
    int frames = 0;
  };

  // A candidate entry of `frame` joins / leaves its object's tally.
  void Count(const Entry& entry, const WindowFrame& frame) {
    Tally& tally = tallies_[entry.object];
    tally.units += frame.best[entry.offset / states_];
    tally.floors += frame.floor;
    ++tally.frames;
  }
  void Uncount(const Entry& entry, const WindowFrame& frame) {
    const auto tally = tallies_.find(entry.object);
    tally->second.units -= frame.best[entry.offset / states_];
    tally->second.floors -= frame.floor;
    if (--tally->second.frames == 0) tallies_.erase(tally);
  }

  // Appends `object`'s emissions in the frame to `stored` (entries left unsorted) and its best
  // emission in BoundUnits, as the HMM over every object computes them.
  void AddEmissions(const IndexedObject& object, WindowFrame& stored, bool candidate = true) const {
    const auto offset = static_cast<std::uint32_t>(stored.emissions.size());
    stored.emissions.resize(offset + static_cast<std::size_t>(states_));
    const std::span<float> emissions(&stored.emissions[offset], static_cast<std::size_t>(states_));
    SectorSimilarityTable::ComputeObject(stored.query, object.Sectors(states_), emissions);
    float sum = 0, best = 0;
    RunHotLoop<EmissionsFromSimilarities>(emissions.data(), states_, &sum, &best, std::size_t{1});
    std::uint16_t units = 0;
    RunHotLoop<BoundUnits>(&best, &units, std::size_t{1});
    stored.best.push_back(units);
    stored.entries.push_back({&object, offset, candidate});
  }

  // Decodes `objects` (lane j for objects[j]) over the window and sets sums[j] to the sum of TC
  // along object j's path; an object a frame did not propose gets its emissions there now (kept
  // for the next answers). lanes_ keeps the objects for Complete.
  void Decode(std::span<const IndexedObject* const> objects, std::vector<double>& sums) {
    const std::size_t frames = frames_.size();
    const std::size_t lanes = objects.size();
    lanes_.assign(objects.begin(), objects.end());
    std::vector<std::uint32_t> offsets(frames * lanes);  // [frame][lane]
    for (std::size_t t = 0; t < frames; ++t) {
      WindowFrame& frame = frames_[t];
      bool added = false;
      for (std::size_t j = 0; j < lanes; ++j) {
        if (const Entry* entry = frame.Find(objects[j])) {
          offsets[t * lanes + j] = entry->offset;
        } else {
          offsets[t * lanes + j] = static_cast<std::uint32_t>(frame.emissions.size());
          AddEmissions(*objects[j], frame, /*candidate=*/false);
          added = true;
        }
      }
      if (added) frame.Sort();
    }
    std::vector<const float*> kept(frames * lanes);
    std::vector<const SparseTransitions*> steps;
    for (std::size_t t = 0; t < frames; ++t) {
      for (std::size_t j = 0; j < lanes; ++j) {
        kept[t * lanes + j] = &frames_[t].emissions[offsets[t * lanes + j]];
      }
      if (t > 0) steps.push_back(&frames_[t].step);
    }
    DecodeKept(kept, frames, lanes, steps, sums);
  }

  std::deque<WindowFrame> frames_;
  std::unordered_map<const IndexedObject*, Tally> tallies_;  // the window's candidates
  std::uint32_t floors_ = 0;                                 // the window frames' floors, summed
  std::vector<const IndexedObject*> lanes_;  // [lane of the last decoding]: the object there
};

// Answers with `every_object_` while the catalogue holds at most candidates_above objects and
// with the HMM over candidates above; see the header.
class CatalogueHmm final : public RecognitionEngine {
 public:
  CatalogueHmm(const EngineOptions& options, std::unique_ptr<RecognitionEngine> every_object)
      : RecognitionEngine("hmm", options),
        every_object_(std::move(every_object)),
        candidates_(std::make_unique<CandidateHmm>(options)),
        active_(every_object_.get()) {
    if (options.candidate_objects == 0) {
      throw std::invalid_argument("the HMM over candidates needs candidate_objects > 0");
    }
  }

  FrameUpdate Observe(std::shared_ptr<const ViewIndexSnapshot> index,
                      const QueryFrame& frame) override {
    RecognitionEngine* chosen = For(index.get());
    FrameUpdate update;
    if (chosen == active_) {
      update = chosen->Observe(index, frame);
    } else {
      // The other engine takes over with the window replayed; on a throw nothing changed.
      std::vector<QueryFrame> frames(window_.begin(), window_.end());
      frames.push_back(frame);
      update = chosen->ObserveSequence(index, frames);
      active_->Reset();
      active_ = chosen;
    }
    window_.push_back(frame);
    if (window_.size() > static_cast<std::size_t>(options().window)) window_.pop_front();
    update.frame_index = frames_seen_++;
    return update;
  }

  FrameUpdate ObserveSequence(std::shared_ptr<const ViewIndexSnapshot> index,
                              std::span<const QueryFrame> frames) override {
    Reset();
    RecognitionEngine* chosen = For(index.get());
    FrameUpdate update = chosen->ObserveSequence(index, frames);
    active_ = chosen;
    const std::size_t kept = std::min(frames.size(), static_cast<std::size_t>(options().window));
    window_.assign(frames.end() - static_cast<std::ptrdiff_t>(kept), frames.end());
    frames_seen_ = update.frame_index + 1;
    return update;
  }

  void Reset() override {
    every_object_->Reset();
    candidates_->Reset();
    active_ = every_object_.get();
    window_.clear();
    frames_seen_ = 0;
  }

  void SetCalibration(std::shared_ptr<const RejectionCalibration> calibration) override {
    every_object_->SetCalibration(calibration);
    candidates_->SetCalibration(std::move(calibration));
  }

 private:
  // The engine for a catalogue of this snapshot's size (a null snapshot is the active engine's
  // to refuse).
  RecognitionEngine* For(const ViewIndexSnapshot* index) const {
    if (index == nullptr) return active_;
    return index->object_count() > static_cast<std::size_t>(options().candidates_above)
               ? candidates_.get()
               : every_object_.get();
  }

  const std::unique_ptr<RecognitionEngine> every_object_;
  const std::unique_ptr<RecognitionEngine> candidates_;
  RecognitionEngine* active_;
  std::deque<QueryFrame> window_;  // the last options().window frames, oldest first
  std::int64_t frames_seen_ = 0;
};

}  // namespace

std::unique_ptr<RecognitionEngine> MakeCandidateHmmEngine(
    const EngineOptions& options, std::unique_ptr<RecognitionEngine> every_object) {
  return std::make_unique<CatalogueHmm>(options, std::move(every_object));
}

}  // namespace orbit
