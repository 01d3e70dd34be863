#include "cli/capture_arguments.h"

#include <unistd.h>

#include <iostream>
#include <stdexcept>

#include "cli/progress_bar.h"

namespace orbit::cli {

void AddCaptureOptions(CLI::App& command, CaptureArguments& arguments) {
  CLI::Option* video = command.add_option(
      "--video", arguments.video,
      "a video of the walk around the object (any format this OpenCV reads: AVI, MP4, ...)");
  command
      .add_option("--orientation", arguments.orientation,
                  "the walk's orientation log, CSV timestamp_ms,azimuth_deg[,elevation_deg] or\n"
                  "frame_index,azimuth_deg[,elevation_deg] (docs/capture.md)")
      ->needs(video);
  video->needs("--orientation");
  std::string trackers;
  for (TrackerKind kind : kTrackerKinds) {
    trackers += "\n  " + std::string(TrackerName(kind)) + ": " + std::string(TrackerSummary(kind));
  }
  // The name is checked by ParseTrackerName when the capture opens.
  command
      .add_option("--tracker", arguments.tracker,
                  "with --video: the tracker following --box (docs/capture.md):" + trackers)
      ->capture_default_str();
}

std::unique_ptr<CaptureReader> OpenCapture(const CaptureArguments& arguments,
                                           const BoxArguments& boxes) {
  CaptureOptions options;
  options.tracker = ParseTrackerName(arguments.tracker);
  if (boxes.box.size() > 1) {
    throw std::invalid_argument("with --video, give one --box: the object on the first frame");
  }
  if (!boxes.box.empty()) options.first_box = ParseBox(boxes.box.front(), "--box");
  if (!boxes.boxes.empty()) options.boxes = ReadBoxesFile(boxes.boxes);
  return std::make_unique<CaptureReader>(
      arguments.video, OrientationLog::ReadFile(arguments.orientation), std::move(options));
}

struct CaptureProgress::Bar {
  ProgressBar bar{std::cerr, ::isatty(STDERR_FILENO) == 1};
};

CaptureProgress::CaptureProgress(bool enabled)
    : bar_(enabled ? std::make_shared<Bar>() : nullptr) {}
CaptureProgress::~CaptureProgress() = default;

void CaptureProgress::operator()(long read, long total) {
  if (!bar_) return;
  bar_->bar.Update("frames", static_cast<std::size_t>(read),
                   static_cast<std::size_t>(std::max(total, read)));
}

}  // namespace orbit::cli
