// SimilarityRows: the Tanimoto coefficients of a session's window frames with the views of the
// few objects its answer looks at closely (the winner, the runner-up), computed once per frame
// and object and kept while the frame stays in the window. The accept / unknown statistic
// (core/decision/unknown_statistic.h) and the pose estimate (core/decision/pose_estimate.h) read
// them; without the cache each update would redo window x views comparisons for both.
//
// Keyed by the IndexedObject's address: when the session moves to another index snapshot, forget
// the objects the new one no longer holds before the old snapshot is released (an object's new
// version is a new IndexedObject, and a freed one's address may be reused); the rows of the
// objects both snapshots share (the same IndexedObject) stay right.
//
// Not thread-safe: one per session.
#pragma once

#include <deque>
#include <span>
#include <vector>

#include "core/descriptor/query_frame.h"
#include "core/index/indexed_object.h"

namespace orbit {

// TC of `frame` with each view of `object`, in the object's view order. With `best_blend`, also
// the highest TC of `frame` with the blend of a pair of IndexedObject::neighbour_pairs (the mean
// of the two views' descriptors, docs/design.md#blended-views), 0 when the object has none; with
// `blends`, the TC with each pair's blend, in neighbour_pairs' order (for a caller that reads
// some of the pairs, not the best of all).
// REQUIRES: every value of `frame` at most 7 (ValidateDescriptorValues; views are checked when
// the object is indexed).
std::vector<float> SimilarityRow(const DescriptorValues& frame, const IndexedObject& object,
                                 float* best_blend = nullptr, std::vector<float>* blends = nullptr);

// The view of a row with the highest TC (the first of equals, as std::max_element finds it),
// and that TC: what the nearest-view blend and the unknown statistic read of most rows.
struct NearestView {
  int view = -1;
  float similarity = 0;
  // The highest TC with a blend of two neighbouring views (SimilarityRow's `best_blend`): what
  // the product's nearest-view term reads beside `similarity`.
  float blended = 0;

  // The nearer of the two: how close the frame comes to the object's views and the blends
  // between them, what the product's nearest-view term and the unknown statistic read.
  float closest() const { return similarity > blended ? similarity : blended; }
};

// One object's rows for a window: rows[k][v] = TC(window frame k, view v).
struct ObjectRows {
  const IndexedObject* object = nullptr;
  std::vector<std::span<const float>> rows;  // one per window frame, oldest first
  std::vector<NearestView> nearest;          // [k]: rows[k]'s, found when it was computed
};

// Asks the CPU for every cache line of `rows` at once. For the rows a caller is about to read
// whole (the winner's: its matched views and pose): with hundreds of sessions on a core, a
// session's older rows are out of cache, and loads issued together wait for memory once
// rather than once per row as a loop reaches them.
void Prefetch(const ObjectRows& rows);

class SimilarityRows {
 public:
  // Mirror the window: a frame entered at its end / left at its front / all left.
  void PushFrame() { frames_.emplace_back(); }
  void DropOldest() { frames_.pop_front(); }
  void Clear() { frames_.clear(); }
  // Drops every row of these objects.
  void Forget(std::span<const IndexedObject* const> objects);

  // The rows of `object` for `window` (the frames pushed so far, oldest first), computing the
  // missing ones. The spans stay valid while their frame and object stay in the cache.
  // REQUIRES: window.size() equals the frames pushed and not dropped.
  ObjectRows For(std::span<const QueryFrame> window, const IndexedObject& object);

 private:
  struct Row {
    const IndexedObject* object = nullptr;
    NearestView nearest;
    std::vector<float> values;
  };
  // [frame]: the rows computed for it, found by a linear search: a frame holds the rows of the
  // few objects its session's answers looked at closely while it was in the window, and a short
  // contiguous array touches fewer cache lines than a hash map's buckets and nodes, which counts
  // when the session's memory is out of cache (hundreds of sessions on one core).
  std::deque<std::vector<Row>> frames_;
};

}  // namespace orbit
