#include "cli/capture_arguments.h"

#include <unistd.h>

#include <iostream>

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
  CLI::Option* box = command
                         .add_option("--box", arguments.box,
                                     "the object's box x,y,w,h on the first frame, in pixels; "
                                     "tracked\nthrough the video (default: the whole frame)")
                         ->needs(video);
  command
      .add_option("--boxes", arguments.boxes,
                  "CSV frame_index,x,y,w,h: the object's box in every frame")
      ->needs(video)
      ->excludes(box);
  std::string trackers;
  for (TrackerKind kind : kTrackerKinds) {
    trackers += (trackers.empty() ? "" : ", ") + std::string(TrackerName(kind));
  }
  // The name is checked by ParseTrackerName when the capture opens.
  command.add_option("--tracker", arguments.tracker, "the tracker following --box: " + trackers)
      ->capture_default_str();
}

std::unique_ptr<CaptureReader> OpenCapture(const CaptureArguments& arguments) {
  CaptureOptions options;
  options.tracker = ParseTrackerName(arguments.tracker);
  if (!arguments.box.empty()) options.first_box = ParseBox(arguments.box);
  if (!arguments.boxes.empty()) options.boxes = ReadBoxesFile(arguments.boxes);
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
