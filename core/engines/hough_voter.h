// VCI: Hough voting over retrieval lists (docs/design.md#vci; the thesis' parts 1 and 2).
//
// Every window frame q_k gets a retrieval list L_k: the N_L views most similar to it in the
// index (ViewIndexSnapshot::Search: the kd-tree re-ranked by exact TC in kKdTree mode). The
// candidates are the objects on any list. A candidate's Hough score is
//
//   H(c_i) = max over paths j (one view of c_i per list) of
//            sum_k TC(q_k, c_{i,j_k}) - w * sum_{k<n} | dBeta(j_k, j_{k+1}) - dAlpha_k |
//
//   dBeta  = alpha(c_{i,j_k}) - alpha(c_{i,j_{k+1}}),  dAlpha_k = alpha(q_k) - alpha(q_{k+1}),
//
// every difference wrapped to (-180, 180] (and dBeta - dAlpha wrapped again, so that a path
// crossing 0/360 costs what it costs anywhere else), then taken in radians. The max is computed
// by dynamic programming over consecutive lists (BestHoughPath), O(n * N_L^2) per candidate,
// never by enumerating the N_L^n paths.
//
// List extension: a candidate missing from some lists is added to each of them with one view:
//   kWeightless  its view most similar to that frame (no IMU);
//   kOriented    its view nearest the orientation the IMU implies: alpha(anchor view) +
//                (alpha(q_k) - alpha(q_m)), the anchor being the candidate's most similar entry
//                on any list (frame m).
// Variants (engine names): kBestMatch "vci-bm" (no extension, w = 0: each list where the
// candidate appears adds its best similarity), kWeightless "vci-w0" (extension, w = 0),
// kOriented "vci" (extension, w = options.orientation_weight).
//
// Reported score: H(c_i) / n. Matched views: the best path's (for vci-bm, the best entry of each
// list holding the candidate).
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "core/engines/recognition_engine.h"

namespace orbit {

// One view of a candidate standing on a frame's list.
struct HoughEntry {
  int view = 0;           // index in the object's ObjectModel::views
  double azimuth = 0;     // alpha(c_{i,j}), degrees
  double similarity = 0;  // TC(q_k, c_{i,j})
};

// |wrap(wrap(beta_k - beta_next) - wrap(alpha_k - alpha_next))| in radians: the orientation
// term of one step of a path. All arguments in degrees.
double OrientationMismatch(double beta_k, double beta_next, double alpha_k, double alpha_next);

// The score of one path: choice[k] indexes entries[k]. Exposed so tests can enumerate paths.
// A step between frames of which one has no azimuth costs no orientation term.
// REQUIRES: entries, frame_azimuths and choice have the same size and each choice is valid.
double HoughPathScore(std::span<const std::vector<HoughEntry>> entries,
                      std::span<const std::optional<double>> frame_azimuths,
                      std::span<const int> choice, double w);

struct HoughPath {
  double score = 0;         // H(c_i)
  std::vector<int> choice;  // choice[k] indexes entries[k]
};

// The best path by dynamic programming (ties: the lower entry index at each step, from the
// last frame backwards).
// Throws std::invalid_argument when entries is empty, a frame has no entry, or the sizes of
// entries and frame_azimuths differ.
HoughPath BestHoughPath(std::span<const std::vector<HoughEntry>> entries,
                        std::span<const std::optional<double>> frame_azimuths, double w);

enum class HoughVariant { kBestMatch, kWeightless, kOriented };

// Throws std::invalid_argument when options are out of range.
std::unique_ptr<RecognitionEngine> MakeHoughEngine(HoughVariant variant,
                                                   const EngineOptions& options);

}  // namespace orbit
