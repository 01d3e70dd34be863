// orbit recognize: streams image files, or a video with its orientation log (docs/capture.md),
// as the frames of one recognition session and prints the server's update for each frame as it
// arrives.
#include <unistd.h>

#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/box_arguments.h"
#include "cli/capture_arguments.h"
#include "cli/commands.h"
#include "cli/image_arguments.h"
#include "cli/network_options.h"
#include "cli/session_flags.h"
#include "cli/update_format.h"
#include "client/capture_session.h"
#include "client/recognition_session.h"
#include "client/rpc_error.h"

namespace orbit::cli {
namespace {

struct RecognizeOptions {
  NetworkOptions network;
  SessionFlags session;
  std::vector<std::string> images;
  std::vector<double> azimuths;
  BoxArguments boxes;
  CaptureArguments capture;
  bool fast = false;
  bool json = false;
};

int RunRecognizeVideo(const RecognizeOptions& options) {
  const std::unique_ptr<CaptureReader> capture = OpenCapture(options.capture, options.boxes);
  const Connection connection(ToConnectionOptions(options.network));
  RecognitionOptions session_options = ToRecognitionOptions(options.session);
  const bool json = options.json;
  session_options.on_update = [json](const v1::SessionUpdate& u) { PrintUpdate(u, json); };
  auto session = RecognitionSession::Open(connection, std::move(session_options));
  CaptureStreamResult streamed;
  {
    // Frames the tracker lost are not sent: the frame numbers of the updates count sent frames.
    try {
      streamed = StreamCapture(
          *session, *capture,
          {.real_time = !options.fast, .progress = CaptureProgress(::isatty(STDOUT_FILENO) != 1)});
    } catch (const RpcError&) {
      // The session ended early; Close() reports why.
    }
  }
  const grpc::Status status = session->Close();
  if (!status.ok()) throw RpcError("Session", status);
  if (streamed.frames_lost > 0) {
    std::cerr << "orbit: " << streamed.frames_lost << " of " << streamed.frames_read
              << " frames not sent: the tracker lost the object\n";
  }
  return 0;
}

int RunRecognize(const RecognizeOptions& options) {
  if (!options.capture.video.empty()) {
    if (!options.images.empty() || !options.azimuths.empty()) {
      throw std::invalid_argument("give --video or --image, not both");
    }
    return RunRecognizeVideo(options);
  }
  if (options.images.empty())
    throw std::invalid_argument("give --image F [--azimuth A], or --video");
  // Every image is read before the session opens: a bad file fails the command at once. No
  // --azimuth at all: frames without azimuth, as from a device without an orientation sensor.
  const bool azimuths = !options.azimuths.empty();
  const std::vector<cv::Mat> frames =
      ReadImageArguments(options.images, options.azimuths, AzimuthArguments::kOnePerImageOrNone);
  const std::vector<std::optional<cv::Rect>> regions =
      ImageRegions(options.boxes, options.images, frames);

  const Connection connection(ToConnectionOptions(options.network));
  RecognitionOptions session_options = ToRecognitionOptions(options.session);
  const bool json = options.json;
  session_options.on_update = [json](const v1::SessionUpdate& u) { PrintUpdate(u, json); };
  auto session = RecognitionSession::Open(connection, std::move(session_options));
  try {
    for (std::size_t i = 0; i < frames.size(); ++i) {
      session->Push(frames[i], azimuths ? std::optional<double>(options.azimuths[i]) : std::nullopt,
                    regions[i]);
    }
  } catch (const RpcError&) {
    // The session ended early; Close() reports why.
  }
  const grpc::Status status = session->Close();
  if (!status.ok()) throw RpcError("Session", status);
  return 0;
}

}  // namespace

void AddRecognizeCommand(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<RecognizeOptions>();
  CLI::App* command = app.add_subcommand(
      "recognize",
      "Stream images as the frames of one recognition session (--image F --azimuth A, once per\n"
      "frame, in capture order; only azimuth differences matter; no --azimuth at all: a device\n"
      "without an orientation sensor; where the object is: --box x,y,w,h once per --image, or\n"
      "--boxes boxes.csv, grown by --box-margin, default the whole image), or a video with its\n"
      "orientation log (--video V --orientation LOG [--box x,y,w,h on the first frame], at the\n"
      "video's own rate unless --fast), and print the server's update\n"
      "for each frame: one line, or with --json one JSON object with frame, decision, move,\n"
      "candidates [{id, name, score}] best first, and processing_time_us.");
  AddNetworkOptions(*command, options->network, /*server_required=*/true);
  AddSessionFlags(*command, options->session);
  command->add_option("--image", options->images, "a frame's image file (repeat)");
  command->add_option("--azimuth", options->azimuths,
                      "that frame's device azimuth in degrees (repeat, in the order of --image; "
                      "give none for frames without azimuth)");
  AddCaptureOptions(*command, options->capture);
  AddBoxOptions(*command, options->boxes);
  command->add_flag("--fast", options->fast,
                    "with --video: send frames as fast as the server allows, not at the video's "
                    "rate");
  command->add_flag("--json", options->json, "one JSON object per update");
  command->callback([options, &exit_code] { exit_code = RunRecognize(*options); });
}

}  // namespace orbit::cli
