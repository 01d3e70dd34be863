// QueryFrame: what a device sends for one frame, the descriptor of the object's region and the
// device's readings (orientation, noise, blur); the input of every engine
// (docs/design.md#notation).
#pragma once

#include <optional>

#include "core/descriptor/descriptor.h"

namespace orbit {

// One arriving frame: the descriptor of the object's region and the device azimuth (degrees,
// any finite value; only differences between frames matter), or none when the device has no
// orientation reading for the frame (no IMU, or `orbit eval --orientation ignore`). A turn is
// known only between two frames that both have one (MeasuredTurn); where it is not, the
// engines assume nothing about it: the HMM lets the object turn to any sector, VCI puts no
// orientation cost on a path and completes a list with the view most similar to the frame.
// `noise_sigma`: the frame's estimated noise deviation in grey levels (core/descriptor/noise_estimate.h),
// and `blur`, its blur in [0, 1] (core/descriptor/blur_estimate.h), when the device measured them; the
// calibrated accept / unknown rule allows noisy and blurred windows more
// (core/decision/quality_allowance.h). No engine's ranking reads them.
struct QueryFrame {
  Descriptor descriptor;
  std::optional<double> azimuth;
  std::optional<double> noise_sigma{};  // initialised: {descriptor, azimuth} needs no more
  std::optional<double> blur{};
};

// AzimuthChange(from, to) when both frames have an azimuth, else nullopt.
std::optional<double> MeasuredTurn(const QueryFrame& from, const QueryFrame& to);

}  // namespace orbit
