// The pose of what is seen: which side of the winner faces the camera at the latest
// frame, and how sure that is.
//
// A rotation search on the winner alone (EIIS' idea for one object; docs/design.md#pose): each
// view azimuth theta of the object is tried as the model azimuth of the latest frame; frame k
// is then expected at theta + (alpha(q_k) - alpha(q_latest)), its measured turn, and is
// compared with the object's view nearest that azimuth:
//   score(theta) = mean over frames k of TC(q_k, NearestView(theta + turn_k))
// Frames without a measured turn to the latest frame (no azimuth) are left out; the latest
// frame always counts. The pose is the theta of the best score (ties: the smaller azimuth), and
// the spread the largest circular distance from it to any theta scoring within
// kPoseSimilarityTolerance of the best: 0 when one side is unmistakable, 180 for an object that
// looks the same all round. With several frames the turns rule out mirror sides that a single
// frame cannot tell apart.
//
// Pure and thread-safe.
#pragma once

#include <span>

#include "core/descriptor/query_frame.h"
#include "core/index/indexed_object.h"
#include "core/index/similarity_rows.h"

namespace orbit {

// Where the winner is seen from (core/decision/pose_estimate.h): the model azimuth (degrees, [0,
// 360), in the object's own model frame) facing the camera at the latest frame, and how far from it
// (degrees, 0..180) other azimuths fit the window's frames about as well: 0 when one side is
// unmistakable, 180 for an object that looks the same from every side.
struct PoseEstimate {
  double azimuth = 0;
  double spread = 180;
};

// Scores within this of the best "look as much like it" (PoseEstimate::spread). A TC step of
// 0.01 is about what 5 degrees of turn changes on a COIL-100 object's neighbouring views.
inline constexpr double kPoseSimilarityTolerance = 0.01;

// Throws std::invalid_argument when `window` is empty or `object` has no views.
PoseEstimate EstimatePose(std::span<const QueryFrame> window, const IndexedObject& object);

// The same from the window's similarity rows of the object (core/index/similarity_rows.h), as
// sessions compute it. REQUIRES: one row per window frame, the window not empty.
PoseEstimate EstimatePose(std::span<const QueryFrame> window, const ObjectRows& object);

}  // namespace orbit
