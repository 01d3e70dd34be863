// Generated walks round a COIL-100 object for the capture tests (evaluation/capture_generator.h):
// a walk's options, and a walk written into a test's folder as a video and its orientation log.
#pragma once

#include <filesystem>
#include <string>

#include "evaluation/capture_generator.h"
#include "tests/support/test_data.h"

namespace orbit::testing {

// `frames` frames of COIL-100 object `object` going `turn_deg` degrees round it at `fps`; the
// generator's defaults otherwise.
inline CaptureGeneratorOptions CoilWalk(int object, int frames,
                                        double turn_deg = CaptureGeneratorOptions{}.turn_deg,
                                        double fps = CaptureGeneratorOptions{}.fps) {
  CaptureGeneratorOptions options;
  options.coil_dir = CoilDir();
  options.object = object;
  options.frames = frames;
  options.turn_deg = turn_deg;
  options.fps = fps;
  return options;
}

// A walk and where it was written: <dir>/walk.avi and <dir>/walk.csv.
struct WrittenWalk {
  GeneratedCapture capture;
  std::string video;
  std::string log;
};

inline WrittenWalk WriteWalk(const ScratchDir& dir, const CaptureGeneratorOptions& options) {
  WrittenWalk walk{GenerateCapture(options), (dir / "walk.avi").string(),
                   (dir / "walk.csv").string()};
  WriteCapture(walk.capture, walk.video, walk.log);
  return walk;
}

}  // namespace orbit::testing
