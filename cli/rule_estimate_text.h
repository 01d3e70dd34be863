// What `orbit info` and `orbit enroll` say of the accept / unknown rule with the objects the
// server holds (v1::RuleEstimate, docs/design.md#known-ceiling): the objects its calibration
// drew from, the shares of enrolled and left-out objects' windows it accepts, and, with few
// objects, that a measured rate can stray far from the estimate.
//
//   accept / unknown  calibrated on 5 objects: of windows of 8 frames, accepts about 99% of
//     the enrolled objects' own and 4% of objects left out (target 17%); the threshold is held
//     at what the enrolled objects' own views need
//     an enrolled object is often answered unknown between its views: enroll a view every
//     15-25 degrees, on the background and in the light it will be seen in  (below 90%)
//     few objects: on objects nobody enrolled the rate can stray far from this estimate
//     (docs/results/recognition.md, "Small catalogues"); enroll more objects to steady it
#pragma once

#include <cstdint>
#include <string>

#include "orbit/v1/models.pb.h"

namespace orbit::cli {

// Fewer objects than this and the text warns that the estimate rests on few objects.
inline constexpr int kFewCalibrationObjects = 20;
// A smaller share of the enrolled objects' own windows accepted and it says how to enroll.
inline constexpr double kFewKnownAccepted = 0.9;

// The lines above, each ending in a newline. `server_objects`: what the server holds now (a
// calibration in progress says so); `target`: the default false-accept rate.
std::string RuleEstimateText(const v1::RuleEstimate& estimate, std::int64_t server_objects,
                             double target);

}  // namespace orbit::cli
