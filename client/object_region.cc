#include "client/object_region.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace orbit {

void CheckBoxMargin(double margin) {
  if (!(margin >= 0 && margin <= 1)) {
    throw std::invalid_argument("box margin must be in 0..1, got " + std::to_string(margin));
  }
}

cv::Rect ObjectRegion(const cv::Rect& box, double margin, cv::Size image, std::string_view origin) {
  CheckBoxMargin(margin);
  const auto refuse = [origin](const std::string& rule) {
    throw std::invalid_argument(std::string(origin) + ": " + rule);
  };
  if (box.width < 1 || box.height < 1) refuse("w and h must be at least 1");
  if (box.x < 0 || box.y < 0) refuse("x and y must be at least 0");
  // In 64 bits: a box read from a file may hold coordinates whose sum overflows an int.
  if (static_cast<long long>(box.x) + box.width > image.width) {
    refuse("x+w must be at most the image's width " + std::to_string(image.width));
  }
  if (static_cast<long long>(box.y) + box.height > image.height) {
    refuse("y+h must be at most the image's height " + std::to_string(image.height));
  }
  // The box lies inside the image, so the grown box's sums cannot overflow either.
  const int dx = static_cast<int>(std::lround(margin * box.width));
  const int dy = static_cast<int>(std::lround(margin * box.height));
  return cv::Rect(box.x - dx, box.y - dy, box.width + 2 * dx, box.height + 2 * dy) &
         cv::Rect(0, 0, image.width, image.height);
}

}  // namespace orbit
