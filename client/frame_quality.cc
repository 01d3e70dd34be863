#include "client/frame_quality.h"

#include <algorithm>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "core/descriptor/blur_estimate.h"
#include "core/descriptor/noise_estimate.h"

namespace orbit {

FrameQuality MeasureFrameQuality(const cv::Mat& image, std::optional<cv::Rect> region) {
  if (image.empty()) throw std::invalid_argument("frame quality of an empty image");
  const cv::Rect whole(0, 0, image.cols, image.rows);
  const cv::Rect area = region.value_or(whole);
  if (area.width <= 0 || area.height <= 0 || (area & whole) != area) {
    throw std::invalid_argument("frame quality region is empty or not inside its image");
  }
  const cv::Mat pixels = image(area);
  cv::Mat grey;
  if (pixels.channels() == 1) {
    grey = pixels;
  } else {
    cv::cvtColor(pixels, grey, pixels.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  }
  cv::Mat laplacian;
  cv::Laplacian(grey, laplacian, CV_32F);
  cv::Scalar mean, deviation;
  cv::meanStdDev(laplacian, mean, deviation);
  return {deviation[0] * deviation[0], EstimateNoiseSigma(pixels), EstimateBlur(grey)};
}

double MinUsableSharpness(const std::vector<FrameQuality>& qualities,
                          const FrameQualityLimits& limits) {
  if (qualities.empty()) return 0;
  std::vector<double> sharpness;
  for (const FrameQuality& q : qualities) sharpness.push_back(q.sharpness);
  std::nth_element(sharpness.begin(), sharpness.begin() + sharpness.size() / 2, sharpness.end());
  return limits.min_relative_sharpness * sharpness[sharpness.size() / 2];
}

bool IsUsableFrame(const FrameQuality& quality, double min_sharpness,
                   const FrameQualityLimits& limits) {
  return quality.sharpness >= min_sharpness && quality.noise_sigma <= limits.max_noise_sigma;
}

v1::FrameQuality ToProtoFrameQuality(const FrameQuality& quality) {
  v1::FrameQuality proto;
  proto.set_sharpness(quality.sharpness);
  proto.set_noise_sigma(quality.noise_sigma);
  proto.set_blur(quality.blur);
  return proto;
}

}  // namespace orbit
