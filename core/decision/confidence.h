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
// Pure and thread-safe.
#pragma once

namespace orbit {

inline constexpr double kConfidenceIntercept = 8.375;     // a
inline constexpr double kConfidenceStatistic = -6.894;    // b
inline constexpr double kConfidenceFrames = 4.043;        // c
inline constexpr double kConfidenceInteraction = -3.325;  // d

// The formula above; 0 for a non-finite U. REQUIRES: frames >= 1.
double Confidence(double unknown_statistic, int frames);

}  // namespace orbit
