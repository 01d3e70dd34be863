// QueryFrame: what a device sends for one frame, the descriptor of the object's region and the
// device's readings (orientation, noise, blur); the input of every engine
// (docs/design.md#notation).
#pragma once

#include <optional>
#include <string_view>

#include "core/descriptor/descriptor.h"

namespace orbit {

// One arriving frame: the descriptor of the object's region and the device azimuth (degrees,
// any finite value; only differences between frames matter), or none when the device has no
// orientation reading for the frame (no IMU, or `orbit eval --orientation ignore`). A turn is
// known only between two frames that both have one (MeasuredTurn); where it is not, the
// engines assume nothing about it: the HMM lets the object turn to any sector, VCI puts no
// orientation cost on a path and completes a list with the view most similar to the frame.
// `noise_sigma`: the frame's estimated noise deviation in grey levels
// (core/descriptor/noise_estimate.h), and `blur`, its blur in [0, 1]
// (core/descriptor/blur_estimate.h), when the device measured them; the calibrated accept / unknown
// rule allows noisy and blurred windows more (core/decision/quality_allowance.h). No engine's
// ranking reads them.
struct QueryFrame {
  Descriptor descriptor;
  std::optional<double> azimuth;
  std::optional<double> noise_sigma{};  // initialised: {descriptor, azimuth} needs no more
  std::optional<double> blur{};
};

// The readings' ranges: those of EstimateNoiseSigma (grey levels) and EstimateBlur.
inline constexpr double kMaxNoiseSigma = 255;
inline constexpr double kMaxBlur = 1;

// What a caller calls a frame's fields in its messages: the engines' words by default, a
// request's field paths on the server.
struct QueryFrameFields {
  std::string_view descriptor = "frame descriptor";
  std::string_view azimuth = "frame azimuth";
  std::string_view noise_sigma = "frame noise_sigma";
  std::string_view blur = "frame blur";
};

// Every range a frame's values must be in, checked here once: throws std::invalid_argument
// naming the first field out of range, "<field> must be a finite number" for an azimuth,
// "<field> must be in [0, 255] grey levels, got <value>" for a noise reading, "<field> must be
// in [0, 1], got <value>" for a blur reading, or as ValidateDescriptorValues for a descriptor
// value above kDescriptorMaxValue.
void ValidateQueryFrame(const QueryFrame& frame, const QueryFrameFields& fields = {});

// AzimuthChange(from, to) when both frames have an azimuth, else nullopt.
std::optional<double> MeasuredTurn(const QueryFrame& from, const QueryFrame& to);

}  // namespace orbit
