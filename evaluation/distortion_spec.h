// Query distortions as `orbit eval --distortions` names them: the protocol's three (df, mb, gn;
// docs/design.md#query-images) and parameterised ones that combine, so that robustness is
// measured along each kind of damage a real camera does, at any strength:
//
//   df                       the view as captured
//   mb                       the protocol's motion blur: mb:len=15:angle=20
//   mb:len=L:angle=A         MotionBlur (core/descriptor/distortion.h), L in [1, 100] pixels, A
//   degrees;
//                            either parameter may be left out (15, 20)
//   gn                       the protocol's noise: gn:var=0.012
//   gn:var=V                 AddGaussianNoise, V in (0, 1] on the [0, 1] intensity scale
//   jpeg:q=Q                 JPEG compression at quality Q in [1, 100] (OpenCV's libjpeg)
//   gain:G                   brightness: every value times G in (0, 10], rounded and clamped
//   lowres:S                 downscaled by S in (0, 1) (area averaging) and back (bilinear)
//   STEP+STEP+...            the steps in order, e.g. mb:len=9:angle=70+gn:var=0.004
//
// A spec's canonical text (DistortionSpec::name) spells every parameter, except that the
// protocol's three keep their short names, so "mb" and "mb:len=15:angle=20" are the same spec
// named "mb". All functions are pure and thread-safe.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <opencv2/core.hpp>

namespace orbit {

struct DistortionStep {
  enum class Kind { kMotionBlur, kGaussianNoise, kJpeg, kGain, kLowResolution };
  Kind kind = Kind::kMotionBlur;
  // The kind's one or two parameters: kMotionBlur (length px, angle degrees), kGaussianNoise
  // (variance), kJpeg (quality), kGain (factor), kLowResolution (scale); `second` only for blur.
  double first = 0;
  double second = 0;

  friend bool operator==(const DistortionStep&, const DistortionStep&) = default;
};

struct DistortionSpec {
  std::vector<DistortionStep> steps;  // empty: df
  std::string name;                   // canonical text, e.g. "gn", "jpeg:q=20+gain:0.6"

  friend bool operator==(const DistortionSpec&, const DistortionSpec&) = default;
};

// Parses `text` (grammar above). Throws std::invalid_argument naming the offending token and
// what is allowed, e.g. "distortion 'mb:len=0': len must be in [1, 100]" or "distortion
// 'blur': unknown kind 'blur' (df, mb, gn, jpeg, gain, lowres)".
DistortionSpec ParseDistortionSpec(std::string_view text);

// `image` with the spec's steps applied in order (8-bit, 1 to 4 channels; JPEG needs 1 or 3).
// `seed` draws the noise: the first noise step uses it as given, so "gn" is exactly the
// protocol's AddGaussianNoise(image, 0.012, seed); a later one uses MixSeed(seed, its position).
// Throws std::invalid_argument for an empty image or one of another type.
cv::Mat ApplyDistortion(const cv::Mat& image, const DistortionSpec& spec, std::uint64_t seed);

}  // namespace orbit
