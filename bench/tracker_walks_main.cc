// build/orbit_tracker_walks: how closely each tracker (client/object_tracker.h) follows the
// object on generated walks (evaluation/capture_generator.h), the walks of the capture tests
// (tests/client/object_tracker_test.cc) for more objects (docs/results/capture.md, "How well
// each tracker follows the object").
//
//   orbit_tracker_walks COIL_DIR TRACKER [FIRST LAST [WIDTH]]
//
// Objects FIRST..LAST (default 1..20), one 48-frame walk each at WIDTH x 3/4 WIDTH pixels
// (default 320, the tests' size), the tracker started on the true box of the first frame. Prints
// one Markdown row per walk: the least and the mean IoU with the true box (a lost frame counts
// 0 in the mean, none in the least), the frames reported lost, and a frame-by-frame trace
// ('.' IoU >= 0.6, 'x' below, 'L' lost); then a summary row. Deterministic.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "client/object_tracker.h"
#include "evaluation/capture_generator.h"

namespace {

using namespace orbit;

constexpr int kFrames = 48;
constexpr double kIouGoal = 0.6;  // the capture tests' goal for every frame reported found

int Run(int argc, char** argv) {
  if (argc != 3 && argc != 5 && argc != 6) {
    std::fprintf(stderr, "usage: orbit_tracker_walks COIL_DIR TRACKER [FIRST LAST [WIDTH]]\n");
    return 2;
  }
  const TrackerKind kind = ParseTrackerName(argv[2]);
  const int first = argc > 3 ? std::atoi(argv[3]) : 1;
  const int last = argc > 4 ? std::atoi(argv[4]) : 20;
  const int width = argc > 5 ? std::atoi(argv[5]) : 320;
  std::printf(
      "| object | least IoU | mean IoU | lost | frames 1-%d |\n| --- | ---: | ---: | ---: | --- "
      "|\n",
      kFrames - 1);
  int held = 0, walks = 0, all_lost = 0;
  double worst = 1;
  for (int object = first; object <= last; ++object) {
    CaptureGeneratorOptions options;
    options.coil_dir = argv[1];
    options.object = object;
    options.frames = kFrames;
    options.frame_size = cv::Size(width, width * 3 / 4);
    const GeneratedCapture walk = GenerateCapture(options);
    ObjectTracker tracker(walk.frames[0], walk.true_boxes[0], kind);
    double least = 1, mean = 0;
    int lost = 0;
    std::string trace;
    for (std::size_t f = 1; f < walk.frames.size(); ++f) {
      const TrackedBox tracked = tracker.Track(walk.frames[f]);
      if (tracked.lost) {
        ++lost;
        trace += 'L';
        continue;
      }
      const double iou = IntersectionOverUnion(tracked.box, walk.true_boxes[f]);
      trace += iou >= kIouGoal ? '.' : 'x';
      least = std::min(least, iou);
      mean += iou / static_cast<double>(walk.frames.size() - 1);
    }
    std::printf("| %d | %.2f | %.2f | %d | `%s` |\n", object, least, mean, lost, trace.c_str());
    ++walks;
    held += least >= kIouGoal && lost == 0 ? 1 : 0;
    all_lost += lost;
    worst = std::min(worst, least);
  }
  std::printf(
      "\n%s: %d of %d walks held (every frame found, IoU >= %.1f); %d of %d frames lost; "
      "least IoU of a frame found %.2f\n",
      argv[2], held, walks, kIouGoal, all_lost, walks * (kFrames - 1), worst);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "orbit_tracker_walks: %s\n", e.what());
    return 1;
  }
}
