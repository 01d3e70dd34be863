// The capture flags of `orbit enroll --video` and `orbit recognize --video` (docs/capture.md):
// the video, its orientation log and where the object is.
#pragma once

#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "client/capture_reader.h"

namespace orbit::cli {

struct CaptureArguments {
  std::string video;        // --video
  std::string orientation;  // --orientation, the CSV log
  std::string box;          // --box x,y,w,h on the first frame, tracked
  std::string boxes;        // --boxes FILE, one box per frame
  std::string tracker = std::string(TrackerName(TrackerKind::kCsrt));  // --tracker
};

// Registers --video, --orientation, --box, --boxes and --tracker on `command`; --orientation
// is needed with --video, --box and --boxes exclude each other.
void AddCaptureOptions(CLI::App& command, CaptureArguments& arguments);

// Opens the capture the flags name. Throws as CaptureReader, OrientationLog::ReadFile,
// ReadBoxesFile, ParseBox and ParseTrackerName do (messages name the file and line).
std::unique_ptr<CaptureReader> OpenCapture(const CaptureArguments& arguments);

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
