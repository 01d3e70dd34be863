#include "cli/box_arguments.h"

#include <stdexcept>

#include "client/capture_reader.h"
#include "evaluation/dataset.h"

namespace orbit::cli {

CLI::Option* AddBoxMarginOption(CLI::App& command, double& margin) {
  return command
      .add_option("--box-margin", margin,
                  "share of a box's width added on its left and right, and of its height above\n"
                  "and below, before it is clipped to the image")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
}

void AddBoxOptions(CLI::App& command, BoxArguments& arguments) {
  CLI::Option* box = command.add_option(
      "--box", arguments.box,
      "the object's box x,y,w,h in pixels: with --image, one per --image in the same order,\n"
      "grown by --box-margin (default: the whole image); with --video, on the first frame,\n"
      "tracked through the video (default: the whole frame)");
  command
      .add_option("--boxes", arguments.boxes,
                  "a CSV of the object's boxes: with --image, path,x,y,w,h (a dataset's\n"
                  "boxes.csv), a row for every --image, grown by --box-margin; with --video,\n"
                  "frame_index,x,y,w,h, the box in every frame")
      ->excludes(box);
  CLI::Option* margin = AddBoxMarginOption(command, arguments.margin);
  if (CLI::Option* video = command.get_option_no_throw("--video")) margin->excludes(video);
}

std::vector<std::optional<cv::Rect>> ImageRegions(const BoxArguments& arguments,
                                                  const std::vector<std::string>& paths,
                                                  const std::vector<cv::Mat>& images) {
  // The images as a dataset's, so that a box is attached and cut as `orbit eval` and
  // `orbit import` attach and cut it.
  std::vector<DatasetImage> boxed(paths.size());
  for (std::size_t i = 0; i < paths.size(); ++i) boxed[i].path = paths[i];
  if (!arguments.box.empty()) {
    if (arguments.box.size() != paths.size()) {
      throw std::invalid_argument("give one --box per --image (" + std::to_string(paths.size()) +
                                  " images, " + std::to_string(arguments.box.size()) + " boxes)");
    }
    for (std::size_t i = 0; i < paths.size(); ++i) {
      const cv::Rect box = ParseBox(arguments.box[i], "--box");
      boxed[i].box = ImageBox{box.x, box.y, box.width, box.height,
                              "--box " + arguments.box[i] + " for " + paths[i]};
      boxed[i].box_margin = arguments.margin;
    }
  } else if (!arguments.boxes.empty()) {
    AttachBoxes(boxed, ReadBoxes(arguments.boxes), arguments.margin);
  }
  std::vector<std::optional<cv::Rect>> regions(paths.size());
  for (std::size_t i = 0; i < paths.size(); ++i) {
    if (boxed[i].box) regions[i] = DescribedRegion(boxed[i], images.at(i).size());
  }
  return regions;
}

}  // namespace orbit::cli
