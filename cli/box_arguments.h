// Where the object is in a command's images: --box, --boxes and --box-margin. For --image
// files (`orbit enroll`, `orbit recognize`) each image is described in its object's region, the
// box grown by the margin and clipped to the image (client/object_region.h,
// docs/design.md#object-region), exactly as `orbit eval --boxes` and `orbit import --boxes`
// describe the same image, box and margin; for a --video, --box is the object on the first
// frame and --boxes a box per frame (cli/capture_arguments.h).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <opencv2/core.hpp>

#include "client/object_region.h"

namespace orbit::cli {

struct BoxArguments {
  std::vector<std::string> box;       // --box x,y,w,h: one per --image, or a video's first frame's
  std::string boxes;                  // --boxes FILE
  double margin = kDefaultBoxMargin;  // --box-margin, for --image files
};

// Registers --box-margin on `command`, the one text and range of every command that takes it.
CLI::Option* AddBoxMarginOption(CLI::App& command, double& margin);

// Registers --box (repeat), --boxes (excludes --box) and --box-margin on a command that takes
// --image files and, when `command` has a --video option, a video (--box-margin excludes it:
// a video's boxes are described as given).
void AddBoxOptions(CLI::App& command, BoxArguments& arguments);

// The region of each of `images`, read from the files `paths`, that the command describes:
// with --box, the boxes in the order of --image; with --boxes, a dataset's boxes.csv
// (`path,x,y,w,h`, evaluation/dataset.h's ReadBoxes), the row of each image's path; nullopt
// (the whole image) for every image without either. Throws std::invalid_argument, before
// anything is sent, for a count of --box other than the images', a malformed --box, an image
// the file has no box for, and a box not inside its image, naming the flag and its value or the
// file and line and the allowed range ("--box 10,10,900,20 for f.png: x+w must be at most the
// image's width 640"); std::runtime_error as ReadBoxes does for a bad file.
std::vector<std::optional<cv::Rect>> ImageRegions(const BoxArguments& arguments,
                                                  const std::vector<std::string>& paths,
                                                  const std::vector<cv::Mat>& images);

}  // namespace orbit::cli
