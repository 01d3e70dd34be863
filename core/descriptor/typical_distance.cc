#include "core/descriptor/typical_distance.h"

#include <stdexcept>

#include "core/descriptor/distortion.h"
#include "core/descriptor/similarity.h"

namespace orbit {

std::array<cv::Mat, kTypicalDistortionCount> TypicalDistortions(const cv::Mat& view,
                                                                std::uint64_t seed) {
  return {MotionBlur(view), AddGaussianNoise(view, kGaussianNoiseVariance, seed)};
}

double TypicalDistance(const DescriptorValues& view, std::span<const DescriptorValues> copies) {
  if (copies.empty()) throw std::invalid_argument("TypicalDistance: no distorted copies");
  double sum = 0;
  for (const DescriptorValues& copy : copies) sum += TanimotoDistance(view, copy);
  return sum / static_cast<double>(copies.size());
}

}  // namespace orbit
