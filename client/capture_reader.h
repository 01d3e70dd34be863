// CaptureReader: a capture as the device recorded it (docs/capture.md) - a video any OpenCV
// reads, its orientation log, and where the object is - read frame by frame with everything
// Orbit needs of each frame: the image, its azimuth, the object's region and the region's
// quality.
//
// Where the object is: a box on the first frame, followed by the tracker
// (client/object_tracker.h); or one box per frame, used as given; or nothing, and the whole
// frame is the object. Frames whose tracking is lost are returned with `lost` set: describe
// none of them (the box would hold background).
//
// Frame times are index / fps (the container's frame rate), from 0 at the first frame.
// Errors: std::runtime_error naming the video when it cannot be opened or read, states no frame
// rate or is a still image (PNG, JPEG, ...: an image states no frame rate);
// std::invalid_argument (naming the file) when the log does not cover the video (checked
// at once when the container states its frame count, else frame by frame), when the boxes do
// not match the frames, or as ObjectTracker for a bad first box.
// Thread safety: none; one reader per thread.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>

#include "client/frame_quality.h"
#include "client/object_tracker.h"
#include "client/orientation_log.h"

namespace orbit {

struct CaptureOptions {
  std::optional<cv::Rect> first_box = std::nullopt;  // the object on the first frame, then tracked
  std::vector<cv::Rect> boxes = {};  // or one box per frame, used as given (no tracking)
  TrackerKind tracker = kDefaultTracker;
};

struct VideoFrame {
  long index = 0;           // 0 for the video's first frame
  double timestamp_ms = 0;  // index / fps, in ms
  cv::Mat image;            // BGR as decoded
  FrameOrientation orientation;
  // The object's region, inside the image; the whole image when no box was given. Meaningless
  // when `lost`.
  cv::Rect region;
  bool lost = false;     // the tracker lost the object: do not describe this frame
  FrameQuality quality;  // of `region` (zero when lost)
};

class CaptureReader {
 public:
  // Opens `video_path` and checks `log` against it. Throws as the header comment says.
  CaptureReader(const std::string& video_path, OrientationLog log, CaptureOptions options = {});
  ~CaptureReader();

  // Reads the next frame into `frame`; false after the last one.
  bool Next(VideoFrame& frame);

  double fps() const { return fps_; }
  // The frame count the container states; 0 when it states none (a stream).
  long frame_count() const { return frame_count_; }
  cv::Size frame_size() const { return frame_size_; }
  const std::string& video_path() const { return video_path_; }

 private:
  std::string video_path_;
  OrientationLog log_;
  CaptureOptions options_;
  cv::VideoCapture video_;
  double fps_ = 0;
  long frame_count_ = 0;
  cv::Size frame_size_;
  long next_index_ = 0;
  std::unique_ptr<ObjectTracker> tracker_;
};

// Reads a boxes file, CSV `frame_index,x,y,w,h` with that header, one line per frame from 0
// in order: the object's box in every frame (the generator's true boxes, or a device's own
// detector). Throws std::invalid_argument naming the file and line for a missing frame, a
// non-integer or negative value; std::runtime_error when the file cannot be read.
std::vector<cv::Rect> ReadBoxesFile(const std::string& path);

// "x,y,w,h" (as `--box` takes it) as a rectangle; throws std::invalid_argument otherwise,
// "WHAT 'TEXT' must be x,y,w,h in pixels (x, y >= 0; w, h > 0)", `what` naming the box (a flag).
cv::Rect ParseBox(const std::string& text, std::string_view what = "box");

}  // namespace orbit
