#include "core/decision/quality_allowance.h"

#include <algorithm>

namespace orbit {

const AllowanceSlopes& AllowanceSlopesFor(DescriptorVariant variant) {
  return HasAppearanceChannels(variant) ? kHsvHogAllowanceSlopes : kCeddAllowanceSlopes;
}

const AllowanceSlopes& KnownAllowanceSlopesFor(DescriptorVariant variant) {
  return HasAppearanceChannels(variant) ? kHsvHogKnownAllowanceSlopes : kCeddKnownAllowanceSlopes;
}

double WindowAllowance(std::optional<double> noise_sigma, std::optional<double> blur,
                       const AllowanceSlopes& slopes) {
  return (noise_sigma ? NoiseAllowance(*noise_sigma, slopes) : 0.0) +
         (blur ? BlurAllowance(*blur, slopes) : 0.0);
}

double NoiseAllowance(double noise_sigma, const AllowanceSlopes& slopes) {
  return slopes.per_grey_level *
         std::clamp(noise_sigma - kCleanNoiseSigma, 0.0, kNoiseAllowanceSpan);
}

double BlurAllowance(double blur, const AllowanceSlopes& slopes) {
  return slopes.per_blur_unit * std::max(0.0, blur - kSharpFrameBlur);
}

std::optional<double> MeanReading(std::span<const std::optional<double>> readings) {
  double sum = 0;
  int count = 0;
  for (const std::optional<double>& reading : readings) {
    if (reading) {
      sum += *reading;
      ++count;
    }
  }
  if (count == 0) return std::nullopt;
  return sum / count;
}

}  // namespace orbit
