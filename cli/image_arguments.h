// The `--image F --azimuth A` pairs of `orbit enroll` and `orbit recognize`: one azimuth per
// image, in the same order.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace orbit::cli {

// Reads every image (client/image_file.h) after checking there is one azimuth per image.
// Throws std::invalid_argument when the counts differ, std::runtime_error naming a file that
// cannot be read.
std::vector<cv::Mat> ReadImageArguments(const std::vector<std::string>& images,
                                        const std::vector<double>& azimuths);

}  // namespace orbit::cli
