// orbit_device_work: one piece of a device's per-frame work, done a given number of times, for
// measuring its cost where Google Benchmark cannot run: counting the instructions a
// cross-built device binary executes under an emulator (bench/count_instructions.sh,
// docs/results/device.md, "Instruction counts under emulation"). Built in every build, the
// device-only one included.
//
//   orbit_device_work WORK TIMES DATA
//
// DATA is the shared data folder. The frames are those of orbit_bench's device benchmarks
// (bench/cedd_bench.cc, bench/capture_bench.cc), so that the counts compare with theirs:
//   VARIANT              the descriptor of that variant (cedd-lire, cedd-full, cedd-robust,
//                        cedd-hsv-hog) of a whole frame: a photograph of the conformance set
//                        resized to 640x480
//   track                the default tracker (client/object_tracker.h) on the next frame of a
//                        generated 640x480 walk round COIL-100 object 5, started on its first
//   quality              the frame quality (client/frame_quality.h) of the next frame of that
//                        walk, in the object's box
//   device-frame:VARIANT all a device computes for a frame before sending it
//                        (client/recognition_session.h, Push): track, then the quality in the
//                        tracked box and the box's descriptor of VARIANT; a lost frame is
//                        neither measured nor described
//   none                 nothing: the program's start alone
// The set-up (reading the photograph, rendering the walk, starting the tracker) does not depend
// on TIMES, so the cost of one more time is the difference between two counts over the
// difference of their TIMES. Prints a checksum of the results, so that no work is optimised
// away, and the frames the tracker lost. Exit status: 0 done, 1 failed, 2 bad usage.
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include <opencv2/imgproc.hpp>

#include "client/frame_quality.h"
#include "client/image_file.h"
#include "client/object_tracker.h"
#include "core/descriptor/cedd.h"
#include "core/descriptor/descriptor.h"
#include "evaluation/capture_generator.h"

namespace {

std::uint64_t Mix(std::uint64_t sum, std::uint64_t value) { return sum * 31 + value; }

std::uint64_t Mix(std::uint64_t sum, const orbit::Descriptor& descriptor) {
  for (std::uint8_t value : descriptor.values) sum = Mix(sum, value);
  return sum;
}

// The frame of bench/cedd_bench.cc.
cv::Mat Photograph(const std::filesystem::path& data) {
  const cv::Mat photo = orbit::ReadImageFile(
      (data / "cedd-conformance/photos/011_2828686873_2fa36f83d7_b.png").string());
  cv::Mat frame;
  cv::resize(photo, frame, cv::Size(640, 480), 0, 0, cv::INTER_AREA);
  return frame;
}

// The walk of bench/capture_bench.cc.
orbit::GeneratedCapture Walk(const std::filesystem::path& data) {
  orbit::CaptureGeneratorOptions options;
  options.coil_dir = data / "coil-100";
  options.object = 5;
  options.frame_size = cv::Size(640, 480);
  options.frames = 72;
  return orbit::GenerateCapture(options);
}

// Follows the walk from its first frame, `times` frames (wrapping round after the last, the
// tracker started again); with `variant`, also measures and describes each tracked box.
std::uint64_t FollowWalk(const orbit::GeneratedCapture& walk, long times,
                         std::optional<orbit::DescriptorVariant> variant, long& lost) {
  std::uint64_t sum = 0;
  auto tracker = std::make_unique<orbit::ObjectTracker>(walk.frames[0], walk.true_boxes[0]);
  std::size_t next = 1;
  for (long i = 0; i < times; ++i) {
    if (next == walk.frames.size()) {
      tracker = std::make_unique<orbit::ObjectTracker>(walk.frames[0], walk.true_boxes[0]);
      next = 1;
    }
    const cv::Mat& frame = walk.frames[next++];
    const orbit::TrackedBox tracked = tracker->Track(frame);
    sum = Mix(sum, static_cast<std::uint64_t>(tracked.box.x * 1000 + tracked.box.y));
    if (tracked.lost) {
      ++lost;
      continue;
    }
    if (variant) {
      sum =
          Mix(sum,
              static_cast<std::uint64_t>(orbit::MeasureFrameQuality(frame, tracked.box).sharpness));
      sum = Mix(sum, orbit::ExtractCedd(frame, *variant, tracked.box));
    }
  }
  return sum;
}

std::uint64_t Quality(const orbit::GeneratedCapture& walk, long times) {
  double sum = 0;
  for (long i = 0; i < times; ++i) {
    const std::size_t f = 1 + static_cast<std::size_t>(i) % (walk.frames.size() - 1);
    const orbit::FrameQuality quality =
        orbit::MeasureFrameQuality(walk.frames[f], walk.true_boxes[f]);
    sum += quality.sharpness + quality.noise_sigma + quality.blur;
  }
  return static_cast<std::uint64_t>(sum);
}

std::uint64_t Describe(const cv::Mat& frame, orbit::DescriptorVariant variant, long times) {
  std::uint64_t sum = 0;
  for (long i = 0; i < times; ++i) sum = Mix(sum, orbit::ExtractCedd(frame, variant));
  return sum;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string usage = " none|VARIANT|track|quality|device-frame:VARIANT TIMES DATA\n";
  if (argc != 4) {
    std::cerr << "usage: " << argv[0] << usage;
    return 2;
  }
  const std::string work = argv[1];
  const std::string device_frame = "device-frame:";
  const bool follows = work == "track" || work.starts_with(device_frame);
  const std::optional<orbit::DescriptorVariant> variant =
      orbit::ParseVariant(work.starts_with(device_frame) ? work.substr(device_frame.size()) : work);
  if (!variant && work != "none" && work != "track" && work != "quality") {
    std::cerr << "orbit_device_work: unknown work " << work << "\nusage: " << argv[0] << usage;
    return 2;
  }
  char* end = nullptr;
  const long times = std::strtol(argv[2], &end, 10);
  if (*end != '\0' || times < 0) {
    std::cerr << "orbit_device_work: TIMES must be a whole number, not " << argv[2] << "\n";
    return 2;
  }
  const std::filesystem::path data = argv[3];
  try {
    std::uint64_t checksum = 0;
    long lost = 0;
    if (follows) {
      checksum = FollowWalk(Walk(data), times, variant, lost);
    } else if (work == "quality") {
      checksum = Quality(Walk(data), times);
    } else if (variant) {
      checksum = Describe(Photograph(data), *variant, times);
    }
    std::cout << work << " x" << times << ": checksum " << checksum << ", frames lost " << lost
              << "\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "orbit_device_work: " << e.what() << "\n";
    return 1;
  }
}
