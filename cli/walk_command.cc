// orbit walk: renders a walk around a COIL-100 object as a device would film it - a video, its
// orientation log and the object's true box in every frame (evaluation/capture_generator.h) -
// to try `orbit enroll --video` and `orbit recognize --video` without a camera, and to test them.
#include <iostream>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "evaluation/capture_generator.h"

namespace orbit::cli {
namespace {

struct WalkOptions {
  CaptureGeneratorOptions generator;
  std::string coil;
  std::string video;
  std::string orientation;
  std::string boxes;
  int width = 320;
  int height = 240;
};

int RunWalk(WalkOptions options) {
  options.generator.coil_dir = options.coil;
  options.generator.frame_size = cv::Size(options.width, options.height);
  const GeneratedCapture capture = GenerateCapture(options.generator);
  WriteCapture(capture, options.video, options.orientation, options.boxes);
  const cv::Rect& box = capture.true_boxes.front();
  // The first box, as `--box` takes it: what a user would draw on the first frame.
  std::cout << "wrote " << options.video << " (" << capture.frames.size() << " frames at "
            << capture.fps << " fps) and " << options.orientation << "; first box " << box.x << ","
            << box.y << "," << box.width << "," << box.height << "\n";
  return 0;
}

}  // namespace

void AddWalkCommand(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<WalkOptions>();
  CaptureGeneratorOptions& g = options->generator;
  CLI::App* command = app.add_subcommand(
      "walk",
      "Render a walk around a COIL-100 object as a device films it: the object on a cluttered,\n"
      "panning background, its box drifting and scaling, some frames blurred or noisy, and an\n"
      "orientation log with 3 degrees of noise and a slow drift (docs/capture.md). Prints the\n"
      "object's box on the first frame, for --box.");
  command->add_option("--coil", options->coil, "the COIL-100 folder (objN__A.png)")->required();
  command->add_option("--object", g.object, "the COIL-100 object, 1..100")
      ->capture_default_str()
      ->check(CLI::Range(1, 100));
  command->add_option("--video", options->video, "the video to write (.avi, Motion-JPEG)")
      ->required();
  command->add_option("--orientation", options->orientation, "the orientation log to write (CSV)")
      ->required();
  command->add_option("--boxes", options->boxes,
                      "also write the true box of every frame (CSV frame_index,x,y,w,h)");
  command->add_option("--frames", g.frames, "frames in the walk")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  command->add_option("--fps", g.fps, "the video's frame rate")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 240.0));
  command->add_option("--start", g.start_azimuth_deg, "azimuth of the first view, degrees")
      ->capture_default_str();
  command->add_option("--turn", g.turn_deg, "degrees walked round the object over the walk")
      ->capture_default_str()
      ->check(CLI::Range(-3600.0, 3600.0));
  command->add_option("--width", options->width, "frame width, pixels")
      ->capture_default_str()
      ->check(CLI::Range(160, 4096));
  command->add_option("--height", options->height, "frame height, pixels")
      ->capture_default_str()
      ->check(CLI::Range(120, 4096));
  command->add_option("--seed", g.seed, "seed of the scene, the log's noise and the noisy frames")
      ->capture_default_str();
  command->callback([options, &exit_code] { exit_code = RunWalk(*options); });
}

}  // namespace orbit::cli
