// The unknown-object statistic of the calibrated accept / unknown rule (the thesis' Th rule
// is core/decision/rejection.h): how far the window's frames lie from the winner, measured
// against how far they lie from the runner-up and against how far the winner's views lie from
// distorted copies of themselves. Small for an object the index knows, near 1 and above for
// one it does not. Engine-agnostic: it reads the frames and the two objects' views, not an
// engine's internal matching.
//
// For each frame q_k of the window (k = 1..n; docs/design.md#unknown-statistic):
//   d1_k = 1 - max_v TC(q_k, v)   over the winner's views v and the blends of its neighbouring
//                                 views (NearestView::closest, docs/design.md#blended-views)
//   d2_k = 1 - max_v TC(q_k, v)   the same over the runner-up's (1 when there is no runner-up)
//   t_k  = Ttyp of the winner's best view (not blend) for q_k
//   U = mean(d1) / mean(d2) + kTypicalTermWeight * mean(d1) / mean(t)
// The second term is dropped when mean(t) is 0 (views enrolled without typical distances).
//
// Why this form (docs/results/recognition.md): the ratio to the runner-up (the nearest-
// neighbour distance ratio test) scales with what a distortion does to every distance at once,
// so blurred or noisy frames of a known object stay below unknown ones; the typical-distance
// term adds what the threshold rule knew, the view's own spread under distortion. The weight was
// chosen on one split of COIL-100 (every tenth object unknown) and checked on the other.
//
// Pure and thread-safe.
#pragma once

#include <span>

#include "core/descriptor/query_frame.h"
#include "core/index/indexed_object.h"
#include "core/index/similarity_rows.h"

namespace orbit {

inline constexpr double kTypicalTermWeight = 0.2;

// U for the window. Throws std::invalid_argument when `window` is empty or `winner` has no
// views.
double UnknownStatistic(std::span<const QueryFrame> window, const IndexedObject& winner,
                        const IndexedObject* runner_up);

// The same from the window's similarity rows (core/index/similarity_rows.h) of the winner and the
// runner-up (null: none), as sessions compute it. REQUIRES: both have the same frames, at least
// one.
double UnknownStatistic(const ObjectRows& winner, const ObjectRows* runner_up);

// U from the per-frame sums, the one formula both the sessions and the calibration use:
// sums over the window of d1, d2 and t as defined above.
double UnknownStatisticOf(double d1_sum, double d2_sum, double typical_sum);

}  // namespace orbit
