// ViewIndex: every view of every known object (descriptor, object, azimuth), searchable by
// Tanimoto similarity (docs/design.md#view-index: VCI's retrieval lists, the baselines'
// scans). Public interface of the index for the engines, the evaluation and the server.
//
//   ViewIndex index(models, {.search = SearchMode::kKdTree});
//   std::shared_ptr<const ViewIndexSnapshot> snapshot = index.Snapshot();
//   std::vector<ViewMatch> list = snapshot->Search(query, /*count=*/4);
//
// Two search modes behind one call (ViewIndexSnapshot::Search):
//   kExact   brute-force Tanimoto over all views (integer dot products, vectorised).
//   kKdTree  FLANN randomised kd-trees over the 144-dim vectors (Euclidean), which propose
//            `kd_candidates` views; those are re-ranked by exact Tanimoto. Approximate: see
//            docs/results/engines-speed.md for recall@N_L against kExact on COIL-100.
//
// Updates without a rebuild from scratch: views live in immutable segments, each with its own
// kd-tree. Add() (and Replace(), a removal and an addition in one step) appends a segment holding
// the new object and merges segments of similar size (log-structured, so each view is re-indexed
// O(log views) times over the index's life); Remove() records the object as deleted and a segment
// is rewritten only when more than half of it is deleted. Searches skip deleted objects.
//
// Snapshots: Snapshot() returns an immutable view of the index at that moment; later Add() and
// Remove() never change it. A session takes the current snapshot for each frame, so an object
// enrolled or deleted is seen from that session's next frame on.
//
// Object candidates: ViewIndexSnapshot::ObjectCandidates proposes the objects whose summaries
// (the means of their views in kSummarySectors equal azimuth sectors, IndexedObject::Sectors)
// are most like a frame, so that an engine can score a few objects of a large catalogue instead
// of all (docs/design.md#object-candidates). kExact scans every summary; kKdTree searches a
// kd-tree of each segment's summaries, built with the segment.
//
// Thread safety: ViewIndex is safe for concurrent use from multiple threads (writers are
// serialised internally; Snapshot() never waits for a segment build). A ViewIndexSnapshot is
// immutable and safe to share read-only across any number of threads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/base/mutex.h"
#include "core/descriptor/descriptor.h"
#include "core/index/indexed_object.h"
#include "core/model/object_model.h"

namespace orbit {

enum class SearchMode {
  kExact,   // brute-force Tanimoto over every view
  kKdTree,  // FLANN kd-trees, candidates re-ranked by exact Tanimoto
};

struct ViewIndexOptions {
  SearchMode search = SearchMode::kExact;
  int kd_trees = 4;  // FLANN randomised kd-trees per segment
  int kd_checks =
      256;  // leaves FLANN visits per segment and query (see docs/results/engines-speed.md)
  int kd_candidates = 32;  // views FLANN proposes for re-ranking (at least the count asked)
  // Threads that build an index in one pass (the constructor of models, ReplaceAll: a server
  // loading its store); Add, Replace and Remove build on the writer's thread alone, so that an
  // enrollment never takes every CPU from the sessions. Above one, a segment of more than
  // kOneThreadBuildsUpTo objects links its summary graph from every thread at once, and the
  // links then depend on the threads' timing: two builds may propose slightly different
  // candidates, as two builds of FLANN's trees do (docs/design.md#view-index).
  int build_threads = 1;
};

// A segment of at most this many objects is built on one thread whatever build_threads says:
// its summary graph is then the same on every build, and it builds in well under a second.
inline constexpr std::size_t kOneThreadBuildsUpTo = 1000;

// Work that compares an object with the whole catalogue (an enrollment's confusable objects, the
// calibrated rule's left-out objects) scans every object up to this many objects, and above it
// scores only the objects ObjectCandidates proposes, each exactly: a scan of every view per view
// costs in proportion to the catalogue (docs/design.md#object-candidates).
inline constexpr std::size_t kScanEveryObjectUpTo = 1000;

// The sectors per object of the summaries that ObjectCandidates searches: the product HMM's
// states, so that its sector sums serve both.
inline constexpr int kSummarySectors = 8;

// An object proposed by ObjectCandidates: its position in ViewIndexSnapshot::objects() and the
// Tanimoto coefficient of its summary most like the query (exact, in float).
struct ObjectCandidate {
  std::size_t position = 0;
  float similarity = 0;
};

// One view found by a search: the object, the position of the view in that object's
// ObjectModel::views, its azimuth and its exact Tanimoto coefficient with the query.
struct ViewMatch {
  ObjectId object = 0;
  int view = 0;
  double azimuth = 0;
  double similarity = 0;  // TC(query, view), in [0, 1]
};

class ViewIndexSnapshot;
struct SnapshotChange;

class ViewIndex {
 public:
  // An empty index of one descriptor variant.
  // Throws std::invalid_argument when an option is out of range (kd_trees, kd_checks,
  // kd_candidates, build_threads < 1).
  explicit ViewIndex(DescriptorVariant variant, ViewIndexOptions options = {});

  // An index of `models`, built in one pass (one segment).
  // Throws std::invalid_argument when `models` is empty (the variant would be unknown: use the
  // other constructor), when the models' variants differ, when two models share an id, when a
  // model has no views, or when a view's azimuth is not finite or a value exceeds 7.
  explicit ViewIndex(std::vector<ObjectModel> models, ViewIndexOptions options = {});

  ViewIndex(const ViewIndex&) = delete;
  ViewIndex& operator=(const ViewIndex&) = delete;

  // Adds one object. Snapshots taken before are unchanged.
  // Throws std::invalid_argument when the model's variant is not the index's, when its id is
  // already present, when it has no views, or when a view is invalid (as above).
  void Add(ObjectModel model) ABSL_LOCKS_EXCLUDED(write_mutex_);

  // Puts `model` in place of the object with its id (adds it when there is none), published as
  // one snapshot: no snapshot ever lacks the object or holds both versions. Snapshots taken
  // before are unchanged. Throws as Add() for an invalid model, changing nothing.
  void Replace(ObjectModel model) ABSL_LOCKS_EXCLUDED(write_mutex_);

  // Puts `models` in place of every object, built in one pass as the constructor builds them
  // and published as one snapshot (a server loading its store while it already listens).
  // Throws as that constructor, except that `models` may be empty, changing nothing.
  void ReplaceAll(std::vector<ObjectModel> models) ABSL_LOCKS_EXCLUDED(write_mutex_);

  // Removes the object; returns false (and changes nothing) when no object has this id.
  bool Remove(ObjectId id) ABSL_LOCKS_EXCLUDED(write_mutex_);

  // The index as it is now. Never null; cheap (no copy of views).
  std::shared_ptr<const ViewIndexSnapshot> Snapshot() const ABSL_LOCKS_EXCLUDED(publish_mutex_);

  // Work done on every new snapshot before it is published, on the writer's thread (Add,
  // Replace, ReplaceAll, Remove), given the snapshot it replaces: for what readers derive from a
  // snapshot on first use (ViewIndexSnapshot::Derived, ChangeSince), so that the first reader
  // finds it ready instead of computing it while the others wait. Only a head start: when it
  // throws, the snapshot is published all the same and readers derive what is missing.
  using SnapshotPreparation =
      std::function<void(const ViewIndexSnapshot& next, const ViewIndexSnapshot& previous)>;
  void PrepareSnapshotsWith(SnapshotPreparation prepare) ABSL_LOCKS_EXCLUDED(write_mutex_);

  DescriptorVariant variant() const { return variant_; }
  const ViewIndexOptions& options() const { return options_; }

 private:
  // Runs prepare_ on `next`, then makes it the current snapshot.
  void Publish(std::shared_ptr<const ViewIndexSnapshot> next)
      ABSL_EXCLUSIVE_LOCKS_REQUIRED(write_mutex_) ABSL_LOCKS_EXCLUDED(publish_mutex_);
  // A snapshot holding exactly `models` (validated as the constructor does).
  std::shared_ptr<const ViewIndexSnapshot> BuildAll(std::vector<ObjectModel> models) const;

  const DescriptorVariant variant_;
  const ViewIndexOptions options_;
  Mutex write_mutex_;  // serialises the writers
  // Held only to copy or replace the pointer, so Snapshot() never waits for a writer's build.
  mutable Mutex publish_mutex_ ABSL_ACQUIRED_AFTER(write_mutex_);
  std::shared_ptr<const ViewIndexSnapshot> current_ ABSL_GUARDED_BY(publish_mutex_);
  SnapshotPreparation prepare_ ABSL_GUARDED_BY(write_mutex_);
};

// An object's place in a snapshot: its data and the slots of its views in the arrays filled by
// ViewIndexSnapshot::SimilarityToEveryView (view v of the object is slot first_slot + v).
struct ObjectSlot {
  const IndexedObject* object = nullptr;
  std::size_t first_slot = 0;
};

// An immutable state of a ViewIndex. Safe to share across threads; all methods are const and
// thread-safe.
class ViewIndexSnapshot {
 public:
  // Private representation, defined in view_index.cc: immutable segments of views, each with
  // the liveness of its objects in this snapshot.
  struct Segment;
  struct SegmentState;

  ViewIndexSnapshot(DescriptorVariant variant, ViewIndexOptions options,
                    std::vector<SegmentState> segments);
  ~ViewIndexSnapshot();

  DescriptorVariant variant() const { return variant_; }
  SearchMode search_mode() const { return options_.search; }

  // The objects present, in a stable order (the order of addition, deleted objects skipped).
  const std::vector<ObjectSlot>& objects() const { return objects_; }
  std::size_t object_count() const { return objects_.size(); }
  std::size_t view_count() const { return view_count_; }

  // The object with this id, or nullptr.
  const IndexedObject* Find(ObjectId id) const;

  // The position in objects() of the object with this id; throws std::out_of_range when the
  // snapshot has no such object.
  std::size_t PositionOf(ObjectId id) const { return position_of_id_.at(id); }

  // A number no other snapshot of this process has (in order of creation).
  std::uint64_t serial() const { return serial_; }

  // CompareSnapshots(before, *this), computed once per `before` and shared: the sessions that
  // meet this snapshot after `before` (all of them, after one enrollment) pay for the change once
  // between them, not once each (with many sessions open, one enrollment would otherwise cost
  // each of them the whole comparison).
  std::shared_ptr<const SnapshotChange> ChangeSince(const ViewIndexSnapshot& before) const;

  // The `count` views most similar to `query` by Tanimoto, best first (ties: lower object
  // position, then lower view index first), using the snapshot's search mode. Returns fewer
  // when the index holds fewer views. In kKdTree mode the list is approximate (a true
  // neighbour can be missed) but every similarity returned is exact.
  // Throws std::invalid_argument when count < 1.
  std::vector<ViewMatch> Search(const DescriptorValues& query, int count) const;

  // The `count` objects whose best summary is most similar to `query` by Tanimoto, best first
  // (ties: lower position first), using the snapshot's search mode; every object when the
  // snapshot holds `count` or fewer. In kKdTree mode the list is approximate (an object that
  // belongs can be missed) but every similarity returned is exact.
  // Throws std::invalid_argument when count < 1.
  std::vector<ObjectCandidate> ObjectCandidates(const DescriptorValues& query, int count) const;

  // Exact search regardless of the snapshot's mode (the reference the kd-tree is measured by).
  std::vector<ViewMatch> SearchExact(const DescriptorValues& query, int count) const;

  // Fills `similarities` (resized to slot_count()) with TC(query, view) for every view slot;
  // slots of deleted objects hold unspecified values. One brute-force pass: the baselines'
  // scan and the `exact-scan` benchmark.
  void SimilarityToEveryView(const DescriptorValues& query, std::vector<float>& similarities) const;
  std::size_t slot_count() const { return slot_count_; }

  // A snapshot holding this one's objects and `models`, built as one new segment of `models`
  // alone: a large model set shared by many slightly different ones (an evaluation's trials
  // among the same distractor objects) costs each only its own objects. Not part of any
  // ViewIndex. Throws std::invalid_argument as the ViewIndex constructor for `models`, and when
  // a model's id is this snapshot's.
  std::shared_ptr<const ViewIndexSnapshot> With(std::vector<ObjectModel> models) const;

  // Data derived from this snapshot once and shared by all its readers (the HMM's sector table,
  // SectorSimilarityTable::Of): the first call with `key` runs `build` and keeps its result for
  // the snapshot's life; every later call returns the same object. A caller that arrives during
  // a build waits for it. `key` names the derivation and its parameter, e.g. {"sectors", 8}.
  using DerivedKey = std::pair<std::string_view, std::int64_t>;
  std::shared_ptr<const void> Derived(
      DerivedKey key, const std::function<std::shared_ptr<const void>()>& build) const
      ABSL_LOCKS_EXCLUDED(derived_mutex_);

 private:
  std::vector<ViewMatch> SearchKdTree(const DescriptorValues& query, int count) const;
  std::vector<ObjectCandidate> CandidatesExact(const DescriptorValues& query, int count) const;
  std::vector<ObjectCandidate> CandidatesKdTree(const DescriptorValues& query, int count) const;
  std::vector<ViewMatch> Best(const std::vector<std::pair<double, std::size_t>>& scored,
                              int count) const;

  DescriptorVariant variant_;
  ViewIndexOptions options_;
  std::vector<SegmentState> segments_;
  std::vector<std::size_t> segment_first_slot_;
  std::vector<ObjectSlot> objects_;
  std::unordered_map<ObjectId, std::size_t> position_of_id_;
  std::vector<std::int32_t> position_of_slot_;  // object position; -1 for deleted objects
  std::vector<std::int32_t> view_of_slot_;      // view index within its object
  // [segment][object of the segment]: its position in objects_, -1 when deleted
  std::vector<std::vector<std::int32_t>> position_of_object_;
  std::vector<std::size_t> segment_live_objects_;  // [segment]
  std::size_t view_count_ = 0;
  std::size_t slot_count_ = 0;
  std::uint64_t serial_ = 0;
  mutable Mutex derived_mutex_;  // held through a build, so that it runs once
  mutable std::map<DerivedKey, std::shared_ptr<const void>> derived_
      ABSL_GUARDED_BY(derived_mutex_);

  friend class ViewIndex;
};

// What changed between two snapshots, object by object. An object's version is one
// IndexedObject, so an object that gained views (ViewIndex::Replace) is both removed and added.
struct SnapshotChange {
  std::vector<const IndexedObject*> removed;  // in `before` and not in `after`, in before's order
  std::vector<ObjectSlot> added;              // in `after` and not in `before`, in after's order
  // Where each of `after`'s objects() comes from, as maximal runs in after's order: `after`'s
  // objects [after, after + length) are `before`'s [source, source + length), or, when
  // `added`, added[source, source + length).
  // What an engine rebuilds a per-object array from with a few block copies.
  struct Run {
    std::size_t after = 0;
    std::size_t source = 0;
    std::size_t length = 0;
    bool added = false;
    friend bool operator==(const Run&, const Run&) = default;
  };
  std::vector<Run> runs;
  bool empty() const { return removed.empty() && added.empty(); }
};

// O(objects). The engines use it (through ViewIndexSnapshot::ChangeSince, which shares it) to
// bring a session's per-frame state to a new snapshot with work proportional to the change
// (RecognitionEngine, "Index updates").
SnapshotChange CompareSnapshots(const ViewIndexSnapshot& before, const ViewIndexSnapshot& after);

}  // namespace orbit
