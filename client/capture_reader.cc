#include "client/capture_reader.h"

#include <cerrno>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>

namespace orbit {
namespace {

// Boxes lie within this many pixels of the origin (a 1M x 1M frame): larger numbers are typing
// errors, and their sums must not overflow.
constexpr long kMaxBoxCoordinate = 1L << 20;

// Four integers separated by commas: x,y,w,h with w, h > 0, x, y >= 0 and x + w, y + h at most
// kMaxBoxCoordinate; nullopt otherwise.
std::optional<cv::Rect> ParseRect(const std::string& text) {
  std::vector<long> values;
  std::stringstream in(text);
  std::string field;
  while (std::getline(in, field, ',')) {
    char* end = nullptr;
    errno = 0;
    const long value = std::strtol(field.c_str(), &end, 10);
    if (field.empty() || *end != '\0' || errno == ERANGE || value < 0 ||
        value > kMaxBoxCoordinate) {
      return std::nullopt;
    }
    values.push_back(value);
  }
  if (values.size() != 4 || values[2] == 0 || values[3] == 0 ||
      values[0] + values[2] > kMaxBoxCoordinate || values[1] + values[3] > kMaxBoxCoordinate) {
    return std::nullopt;
  }
  return cv::Rect(static_cast<int>(values[0]), static_cast<int>(values[1]),
                  static_cast<int>(values[2]), static_cast<int>(values[3]));
}

}  // namespace

cv::Rect ParseBox(const std::string& text, std::string_view what) {
  const std::optional<cv::Rect> box = ParseRect(text);
  if (!box) {
    throw std::invalid_argument(std::string(what) + " '" + text +
                                "' must be x,y,w,h in pixels (x, y >= 0; w, h > 0)");
  }
  return *box;
}

std::vector<cv::Rect> ReadBoxesFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read boxes file " + path);
  std::vector<cv::Rect> boxes;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    if (line == "frame_index,x,y,w,h") continue;
    const auto comma = line.find(',');
    const std::string where = path + ":" + std::to_string(number);
    if (comma == std::string::npos || line.substr(0, comma) != std::to_string(boxes.size())) {
      throw std::invalid_argument(where + ": expected frame_index " + std::to_string(boxes.size()) +
                                  " (one line per frame, from 0, in order: frame_index,x,y,w,h)");
    }
    const std::optional<cv::Rect> box = ParseRect(line.substr(comma + 1));
    if (!box) {
      throw std::invalid_argument(where + ": '" + line.substr(comma + 1) +
                                  "' must be x,y,w,h in pixels (x, y >= 0; w, h > 0)");
    }
    boxes.push_back(*box);
  }
  if (boxes.empty()) throw std::invalid_argument(path + ": no boxes");
  return boxes;
}

CaptureReader::CaptureReader(const std::string& video_path, OrientationLog log,
                             CaptureOptions options)
    : video_path_(video_path), log_(std::move(log)), options_(std::move(options)) {
  if (options_.first_box && !options_.boxes.empty()) {
    throw std::invalid_argument("give the object's first box or a box per frame, not both");
  }
  if (!std::filesystem::is_regular_file(video_path)) {
    throw std::runtime_error("cannot read video " + video_path + ": no such file");
  }
  // A video reader opens a still image too, as one frame at a rate the reader makes up: the
  // image states no frame rate, so it is refused as such a video is (docs/capture.md, "The
  // format"). Still images are told by their content, not their name.
  if (cv::haveImageReader(video_path)) {
    throw std::runtime_error("video " + video_path +
                             " is a still image: it states no frame rate, so no frame time can be "
                             "aligned to the orientation log; give the video of the walk");
  }
  if (!video_.open(video_path) || !video_.isOpened()) {
    throw std::runtime_error(
        "cannot read video " + video_path +
        ": no OpenCV reader opens it (not a video, or a format this OpenCV cannot decode)");
  }
  fps_ = video_.get(cv::CAP_PROP_FPS);
  if (!(fps_ > 0 && std::isfinite(fps_))) {
    throw std::runtime_error("video " + video_path +
                             " states no frame rate: frame times cannot be aligned to the log");
  }
  frame_count_ = std::max(0L, static_cast<long>(video_.get(cv::CAP_PROP_FRAME_COUNT)));
  frame_size_ = cv::Size(static_cast<int>(video_.get(cv::CAP_PROP_FRAME_WIDTH)),
                         static_cast<int>(video_.get(cv::CAP_PROP_FRAME_HEIGHT)));
  if (!options_.boxes.empty() && frame_count_ > 0 &&
      static_cast<long>(options_.boxes.size()) < frame_count_) {
    throw std::invalid_argument("the boxes give " + std::to_string(options_.boxes.size()) +
                                " frames, video " + video_path + " has " +
                                std::to_string(frame_count_));
  }
  log_.RequireCovers(frame_count_, (frame_count_ - 1) * 1000 / fps_);
}

CaptureReader::~CaptureReader() = default;

bool CaptureReader::Next(VideoFrame& frame) {
  cv::Mat image;
  if (!video_.read(image) || image.empty()) return false;
  frame = VideoFrame();
  frame.index = next_index_++;
  frame.timestamp_ms = frame.index * 1000 / fps_;
  frame.image = image;
  frame.orientation = log_.At(frame.index, frame.timestamp_ms);
  const cv::Rect whole(0, 0, image.cols, image.rows);
  frame.region = whole;
  if (!options_.boxes.empty()) {
    if (frame.index >= static_cast<long>(options_.boxes.size())) {
      throw std::invalid_argument("no box for frame " + std::to_string(frame.index) + " of " +
                                  video_path_ + ": the boxes give " +
                                  std::to_string(options_.boxes.size()) + " frames");
    }
    frame.region = options_.boxes[frame.index] & whole;
    frame.lost = frame.region.area() == 0;
  } else if (options_.first_box) {
    if (!tracker_) {
      tracker_ = std::make_unique<ObjectTracker>(image, *options_.first_box, options_.tracker);
      frame.region = *options_.first_box;
    } else {
      const TrackedBox tracked = tracker_->Track(image);
      frame.region = tracked.box;
      frame.lost = tracked.lost;
    }
  }
  if (!frame.lost) frame.quality = MeasureFrameQuality(image, frame.region);
  return true;
}

}  // namespace orbit
