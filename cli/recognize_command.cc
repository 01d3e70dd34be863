// orbit recognize: streams image files as the frames of one recognition session and prints the
// server's update for each frame as it arrives.
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/image_arguments.h"
#include "cli/network_options.h"
#include "cli/session_flags.h"
#include "cli/update_format.h"
#include "client/recognition_session.h"
#include "client/rpc_error.h"

namespace orbit::cli {
namespace {

struct RecognizeOptions {
  NetworkOptions network;
  SessionFlags session;
  std::vector<std::string> images;
  std::vector<double> azimuths;
  bool json = false;
};

int RunRecognize(const RecognizeOptions& options) {
  // Every image is read before the session opens: a bad file fails the command at once. No
  // --azimuth at all: frames without azimuth, as from a device without an orientation sensor.
  const bool azimuths = !options.azimuths.empty();
  const std::vector<cv::Mat> frames = ReadImageArguments(
      options.images, azimuths ? options.azimuths : std::vector<double>(options.images.size()));

  const Connection connection(ToConnectionOptions(options.network));
  SessionOptions session_options = ToSessionOptions(options.session);
  const bool json = options.json;
  session_options.on_update = [json](const v1::SessionUpdate& u) { PrintUpdate(u, json); };
  auto session = RecognitionSession::Open(connection, std::move(session_options));
  try {
    for (std::size_t i = 0; i < frames.size(); ++i) {
      session->Push(frames[i],
                    azimuths ? std::optional<double>(options.azimuths[i]) : std::nullopt);
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
      "without an orientation sensor) and print the server's update\n"
      "for each frame: one line, or with --json one JSON object with frame, decision, move,\n"
      "candidates [{id, name, score}] best first, and processing_time_us.");
  AddNetworkOptions(*command, options->network, /*server_required=*/true);
  AddSessionFlags(*command, options->session);
  command->add_option("--image", options->images, "a frame's image file (repeat)")->required();
  command->add_option("--azimuth", options->azimuths,
                      "that frame's device azimuth in degrees (repeat, in the order of --image; "
                      "give none for frames without azimuth)");
  command->add_flag("--json", options->json, "one JSON object per update");
  command->callback([options, &exit_code] { exit_code = RunRecognize(*options); });
}

}  // namespace orbit::cli
