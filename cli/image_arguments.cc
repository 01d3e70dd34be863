#include "cli/image_arguments.h"

#include <stdexcept>

#include "client/image_file.h"

namespace orbit::cli {

std::vector<cv::Mat> ReadImageArguments(const std::vector<std::string>& images,
                                        const std::vector<double>& azimuths) {
  if (images.size() != azimuths.size()) {
    throw std::invalid_argument("give one --azimuth per --image (" + std::to_string(images.size()) +
                                " images, " + std::to_string(azimuths.size()) + " azimuths)");
  }
  std::vector<cv::Mat> pixels;
  for (const std::string& file : images) pixels.push_back(ReadImageFile(file));
  return pixels;
}

}  // namespace orbit::cli
