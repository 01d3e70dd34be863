// The confidence of an update (issue 12): how likely the top-1 object is the object in front of
// the camera, in [0, 1], meant literally: among updates with confidence about 0.9, about 90%
// are right.
//
//   confidence = 1 / (1 + exp(-(kConfidenceIntercept - kConfidenceSlope * U)))
//
// with U the window's unknown statistic (core/unknown_statistic.h). A logistic fit of "top-1
// right" on U over every update of `orbit eval --methods product --unknown-objects
// 10,20,...,100 --n 1,8` (known and unknown objects, DF, MB and GN, 10 trials); checked on the
// other split (objects 91-100 unknown) in docs/results/recognition.md's reliability table.
// It holds for the product pipeline on model sets like COIL-100's; for another engine or
// variant it is an estimate.
//
// Pure and thread-safe.
#pragma once

namespace orbit {

inline constexpr double kConfidenceIntercept = 10.18;
inline constexpr double kConfidenceSlope = 8.35;

// The formula above; 0 for a non-finite U.
double Confidence(double unknown_statistic);

}  // namespace orbit
