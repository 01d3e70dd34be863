#include "cli/image_arguments.h"

#include <stdexcept>

#include "client/image_file.h"

namespace orbit::cli {
namespace {

// "1 image", "3 images".
std::string Count(std::size_t n, const std::string& thing) {
  return std::to_string(n) + " " + thing + (n == 1 ? "" : "s");
}

}  // namespace

std::vector<cv::Mat> ReadImageArguments(const std::vector<std::string>& images,
                                        const std::vector<double>& azimuths,
                                        AzimuthArguments rule) {
  const bool none_allowed = rule == AzimuthArguments::kOnePerImageOrNone;
  if (images.size() != azimuths.size() && !(none_allowed && azimuths.empty())) {
    throw std::invalid_argument(
        Count(images.size(), "image") + " and " + Count(azimuths.size(), "azimuth") +
        ": give one --azimuth per --image" +
        (none_allowed ? ", or no --azimuth at all (frames without azimuth, as from a device "
                        "without a compass)"
                      : ""));
  }
  std::vector<cv::Mat> pixels;
  for (const std::string& file : images) pixels.push_back(ReadImageFile(file));
  return pixels;
}

}  // namespace orbit::cli
