// The capture flags of `orbit enroll --video` and `orbit recognize --video` (docs/capture.md):
// the video, its orientation log and the tracker; where the object is comes from the command's
// --box or --boxes (cli/box_arguments.h).
#pragma once

#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/box_arguments.h"
#include "client/capture_reader.h"

namespace orbit::cli {

struct CaptureArguments {
  std::string video;        // --video
  std::string orientation;  // --orientation, the CSV log
  // --tracker
  std::string tracker = std::string(TrackerName(kDefaultTracker));
};

// Registers --video, --orientation and --tracker on `command`; --orientation is needed with
// --video.
void AddCaptureOptions(CLI::App& command, CaptureArguments& arguments);

// Opens the capture the flags name, the object on the first frame (one --box, tracked) or in
// every frame (--boxes FILE, CSV frame_index,x,y,w,h). Throws std::invalid_argument for more
// than one --box, and as CaptureReader, OrientationLog::ReadFile, ReadBoxesFile, ParseBox and
// ParseTrackerName do (messages name the flag, or the file and line).
std::unique_ptr<CaptureReader> OpenCapture(const CaptureArguments& arguments,
                                           const BoxArguments& boxes);

// The progress callback of a capture: a bar on stderr ("frames"), drawn by cli/progress_bar.h
// for runs longer than two seconds; nothing when `enabled` is false (`orbit recognize` printing
// its updates on the same terminal, where they show the progress and a bar would break them).
class CaptureProgress {
 public:
  explicit CaptureProgress(bool enabled = true);
  ~CaptureProgress();
  void operator()(long read, long total);

 private:
  struct Bar;
  std::shared_ptr<Bar> bar_;
};

}  // namespace orbit::cli
