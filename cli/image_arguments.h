// The `--image F --azimuth A` pairs of `orbit enroll` and `orbit recognize`: one azimuth per
// image, in the same order; for `orbit recognize` also no azimuth at all, the frames of a device
// without a compass.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace orbit::cli {

// Which counts of --azimuth a command takes.
enum class AzimuthArguments {
  kOnePerImage,        // `orbit enroll`: every view is placed by its azimuth
  kOnePerImageOrNone,  // `orbit recognize`: none at all for frames without azimuth
};

// Reads every image (client/image_file.h) after checking the count of azimuths against `rule`.
// Throws std::invalid_argument when it does not match, stating the counts the command takes and
// the ones given; std::runtime_error naming a file that cannot be read.
std::vector<cv::Mat> ReadImageArguments(const std::vector<std::string>& images,
                                        const std::vector<double>& azimuths, AzimuthArguments rule);

}  // namespace orbit::cli
