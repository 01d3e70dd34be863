#include "evaluation/distortion_spec.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <initializer_list>
#include <optional>
#include <span>
#include <stdexcept>
#include <system_error>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "core/base/seeded_random.h"
#include "core/descriptor/distortion.h"

namespace orbit {
namespace {

using Kind = DistortionStep::Kind;

std::vector<std::string_view> Split(std::string_view text, char separator) {
  std::vector<std::string_view> parts;
  std::size_t start = 0;
  for (;;) {
    const std::size_t end = text.find(separator, start);
    parts.push_back(text.substr(start, end == std::string_view::npos ? end : end - start));
    if (end == std::string_view::npos) return parts;
    start = end + 1;
  }
}

std::string Number(double value) {
  char buffer[32];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, end);
}

// Reads one step; `step_text` is quoted in errors.
class StepParser {
 public:
  explicit StepParser(std::string_view step_text) : text_(step_text) {}

  [[noreturn]] void Fail(const std::string& problem) const {
    throw std::invalid_argument("distortion '" + std::string(text_) + "': " + problem);
  }

  // A finite number in [low, high] (each bound inclusive unless the open flag says otherwise).
  double Value(std::string_view what, std::string_view token, double low, double high,
               bool low_open, bool high_open) const {
    double value = 0;
    const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
    std::string range(low_open ? "(" : "[");
    range.append(Number(low)).append(", ").append(Number(high)).append(high_open ? ")" : "]");
    if (token.empty() || error != std::errc() || end != token.data() + token.size() ||
        !std::isfinite(value)) {
      Fail(std::string(what) + " must be a number in " + range + ", not '" + std::string(token) +
           "'");
    }
    if (value < low || value > high || (low_open && value == low) || (high_open && value == high)) {
      Fail(std::string(what) + " must be in " + range);
    }
    return value;
  }

  // The value of `key=...` among `params`, or nullopt when absent; a parameter of another name
  // is refused.
  std::optional<std::string_view> Named(std::span<const std::string_view> params,
                                        std::string_view key,
                                        std::initializer_list<std::string_view> allowed) const {
    std::optional<std::string_view> found;
    for (const std::string_view param : params) {
      const std::size_t equals = param.find('=');
      const std::string_view name = param.substr(0, equals);
      if (std::find(allowed.begin(), allowed.end(), name) == allowed.end() ||
          equals == std::string_view::npos) {
        std::string list;
        for (const std::string_view a : allowed)
          list += (list.empty() ? "" : ", ") + std::string(a) + "=";
        Fail("unknown parameter '" + std::string(param) + "' (" + list + ")");
      }
      if (name == key) {
        if (found) Fail(std::string(key) + " is given twice");
        found = param.substr(equals + 1);
      }
    }
    return found;
  }

  DistortionStep Parse() const {
    if (text_.empty()) Fail("empty step");
    const std::vector<std::string_view> parts = Split(text_, ':');
    const std::string_view kind = parts[0];
    const std::span<const std::string_view> params(parts.begin() + 1, parts.end());
    if (kind == "mb") {
      const auto length = Named(params, "len", {"len", "angle"});
      const auto angle = Named(params, "angle", {"len", "angle"});
      return {Kind::kMotionBlur,
              length ? Value("len", *length, 1, 100, false, false) : kMotionBlurLength,
              angle ? Value("angle", *angle, -360, 360, false, false) : kMotionBlurAngleDegrees};
    }
    if (kind == "gn") {
      const auto variance = Named(params, "var", {"var"});
      return {Kind::kGaussianNoise,
              variance ? Value("var", *variance, 0, 1, true, false) : kGaussianNoiseVariance, 0};
    }
    if (kind == "jpeg") {
      const auto quality = Named(params, "q", {"q"});
      if (!quality) Fail("needs q=Q, the quality in [1, 100]");
      const double q = Value("q", *quality, 1, 100, false, false);
      if (q != std::round(q)) Fail("q must be a whole number in [1, 100]");
      return {Kind::kJpeg, q, 0};
    }
    if (kind == "gain" || kind == "lowres") {
      if (params.size() != 1)
        Fail(std::string("needs one value, e.g. ") + std::string(kind) +
             (kind == "gain" ? ":0.6" : ":0.5"));
      if (kind == "gain") return {Kind::kGain, Value("gain", params[0], 0, 10, true, false), 0};
      return {Kind::kLowResolution, Value("lowres", params[0], 0, 1, true, true), 0};
    }
    Fail("unknown kind '" + std::string(kind) + "' (df, mb, gn, jpeg, gain, lowres)");
  }

 private:
  std::string_view text_;
};

std::string StepName(const DistortionStep& step) {
  switch (step.kind) {
    case Kind::kMotionBlur:
      if (step.first == kMotionBlurLength && step.second == kMotionBlurAngleDegrees) return "mb";
      return "mb:len=" + Number(step.first) + ":angle=" + Number(step.second);
    case Kind::kGaussianNoise:
      if (step.first == kGaussianNoiseVariance) return "gn";
      return "gn:var=" + Number(step.first);
    case Kind::kJpeg: return "jpeg:q=" + Number(step.first);
    case Kind::kGain: return "gain:" + Number(step.first);
    case Kind::kLowResolution: return "lowres:" + Number(step.first);
  }
  return "";
}

cv::Mat Jpeg(const cv::Mat& image, int quality) {
  if (image.channels() != 1 && image.channels() != 3) {
    throw std::invalid_argument("jpeg: the image must have 1 or 3 channels, not " +
                                std::to_string(image.channels()));
  }
  std::vector<std::uint8_t> bytes;
  cv::imencode(".jpg", image, bytes, {cv::IMWRITE_JPEG_QUALITY, quality});
  return cv::imdecode(bytes, image.channels() == 1 ? cv::IMREAD_GRAYSCALE : cv::IMREAD_COLOR);
}

cv::Mat LowResolution(const cv::Mat& image, double scale) {
  const cv::Size small(std::max(1, static_cast<int>(std::lround(image.cols * scale))),
                       std::max(1, static_cast<int>(std::lround(image.rows * scale))));
  cv::Mat reduced, restored;
  cv::resize(image, reduced, small, 0, 0, cv::INTER_AREA);
  cv::resize(reduced, restored, image.size(), 0, 0, cv::INTER_LINEAR);
  return restored;
}

}  // namespace

DistortionSpec ParseDistortionSpec(std::string_view text) {
  DistortionSpec spec;
  if (text == "df") {
    spec.name = "df";
    return spec;
  }
  if (text.empty()) throw std::invalid_argument("distortion '': empty (e.g. df, mb, gn:var=0.004)");
  for (const std::string_view step_text : Split(text, '+')) {
    if (step_text == "df") {
      throw std::invalid_argument("distortion '" + std::string(text) +
                                  "': df means no distortion and cannot be combined");
    }
    spec.steps.push_back(StepParser(step_text).Parse());
    if (!spec.name.empty()) spec.name += '+';
    spec.name += StepName(spec.steps.back());
  }
  return spec;
}

cv::Mat ApplyDistortion(const cv::Mat& image, const DistortionSpec& spec, std::uint64_t seed) {
  if (image.empty() || image.depth() != CV_8U || image.channels() > 4) {
    throw std::invalid_argument("ApplyDistortion: the image must be 8-bit with 1-4 channels");
  }
  cv::Mat out = image.clone();
  bool noise_seeded = false;
  for (std::size_t s = 0; s < spec.steps.size(); ++s) {
    const DistortionStep& step = spec.steps[s];
    switch (step.kind) {
      case Kind::kMotionBlur: out = MotionBlur(out, step.first, step.second); break;
      case Kind::kGaussianNoise:
        out = AddGaussianNoise(out, step.first, noise_seeded ? MixSeed(seed, s) : seed);
        noise_seeded = true;
        break;
      case Kind::kJpeg: out = Jpeg(out, static_cast<int>(step.first)); break;
      case Kind::kGain: out.convertTo(out, CV_8U, step.first); break;
      case Kind::kLowResolution: out = LowResolution(out, step.first); break;
    }
  }
  return out;
}

}  // namespace orbit
