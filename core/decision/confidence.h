// The confidence of an update: how likely the top-1 object is the object in front of
// the camera, in [0, 1], meant literally: among updates with confidence about 0.9, about 90%
// are right.
//
//   z = a + b U + c ln n + d U ln n,   confidence = 1 / (1 + exp(-z))
//
// with U the window's unknown statistic (core/decision/unknown_statistic.h) and n its frames (a
// longer window makes the same U more telling). A logistic fit of "top-1 right" over every update
// of `orbit eval --methods product --unknown-objects 10,20,...,100` (known and unknown objects, DF,
// MB and GN, n = 1, 2, 4, 6, 8, 10 trials), checked on the other split (objects 91-100 unknown) in
// docs/results/recognition.md's reliability table. It holds for the product pipeline on model sets
// like COIL-100's; for another engine or variant it is an estimate.
//
// With a calibration of the model set (core/decision/rejection_calibration.h) the server says
// instead what its own catalogue says (CatalogueConfidence, below): the curve above was fitted on
// COIL-100, and among look-alikes the same U is right far more often than there.
//
// Pure and thread-safe.
#pragma once

#include "core/decision/rejection_calibration.h"

namespace orbit {

inline constexpr double kConfidenceIntercept = 8.375;     // a
inline constexpr double kConfidenceStatistic = -6.894;    // b
inline constexpr double kConfidenceFrames = 4.043;        // c
inline constexpr double kConfidenceInteraction = -3.325;  // d

// The formula above; 0 for a non-finite U. REQUIRES: frames >= 1.
double Confidence(double unknown_statistic, int frames);

// The catalogue's confidence (docs/design.md#confidence), the product's whenever the session has
// a calibration with known windows; the formula above otherwise. The calibration holds, per window
// length, the U of the enrolled objects' own windows (answered right) and of left-out objects'
// windows (answered wrong). The windows of both sets nearest to the window's U, taken one at a
// time until they hold kConfidenceNeighbourhood as shares of their sets (summed), hold shares
// `known` and `left_out` of them, and
//
//   confidence = p known / (p known + (1 - p) left_out),      p = kRightPrior
//
// the share of right answers among windows like this one, in a stream where p of the windows
// are answered right before their U is seen. Each set is judged at its own U: the known windows
// at U less the known allowance, the left-out ones at U less the null's
// (core/decision/quality_allowance.h), as the rule judges them.
inline constexpr double kRightPrior = 0.8;
inline constexpr double kConfidenceNeighbourhood = 0.05;

// 0 for a non-finite U. REQUIRES: calibration.calibrated(), calibration.has_known_windows(),
// frames >= 1.
double CatalogueConfidence(const RejectionCalibration& calibration, double judged_as_known,
                           double judged, int frames);

}  // namespace orbit
