// orbit demo: shows the product working with no dataset. Renders a few textured objects
// (evaluation/synthetic_object.h), enrolls those the server does not hold yet, then streams a
// session around one of them - from azimuths between the enrolled views, with a compass offset
// the server cannot know - and prints every update.
#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "cli/commands.h"
#include "cli/network_options.h"
#include "cli/session_flags.h"
#include "cli/update_format.h"
#include "client/enroller.h"
#include "client/models_client.h"
#include "client/recognition_session.h"
#include "client/rpc_error.h"
#include "evaluation/synthetic_object.h"

namespace orbit::cli {
namespace {

constexpr int kEnrolledViews = 36;  // every 10 degrees

struct DemoOptions {
  NetworkOptions network;
  SessionFlags session;
  std::string object = "demo-can";
  double start = 125;  // first frame's true azimuth, degrees
  double step = 10;    // the device turns this much between frames
  int frames = 8;
  double compass_offset = 73;  // device azimuth = true azimuth + offset
  std::string save_views;      // folder for the rendered images, when given
  bool json = false;
};

void Save(const std::string& folder, const std::string& name, const cv::Mat& image) {
  if (folder.empty()) return;
  std::filesystem::create_directories(folder);
  const std::string file = (std::filesystem::path(folder) / name).string();
  if (!cv::imwrite(file, image)) throw std::runtime_error("cannot write " + file);
}

// Enrolls `object` unless the server holds an object of that name already.
void EnrollIfMissing(const Connection& connection, const SyntheticObject& object,
                     const std::string& save_views) {
  try {
    const v1::GetObjectResponse existing =
        ModelsClient(connection).GetObject(ObjectByName(object.name));
    std::cout << object.name << ": already enrolled (id " << existing.object().id() << ", "
              << existing.object().view_count() << " views)\n";
    return;
  } catch (const RpcError& e) {
    if (e.code() != grpc::StatusCode::NOT_FOUND) throw;
  }
  std::vector<EnrollmentImage> images;
  for (int v = 0; v < kEnrolledViews; ++v) {
    const double azimuth = v * 360.0 / kEnrolledViews;
    images.push_back({RenderView(object, azimuth), azimuth, {}, {}});
    Save(save_views, object.name + "__" + std::to_string(static_cast<int>(azimuth)) + ".png",
         images.back().image);
  }
  Enroller enroller(connection);
  const v1::ObjectInfo info = enroller.Enroll(object.name, images, R"({"source":"orbit demo"})");
  std::cout << object.name << ": enrolled (id " << info.id() << ", " << info.view_count()
            << " views, rendered every " << 360 / kEnrolledViews << " degrees)\n";
}

int RunDemo(const DemoOptions& options) {
  const std::vector<SyntheticObject> objects = DemoObjects();
  const SyntheticObject* shown = nullptr;
  for (const SyntheticObject& object : objects) {
    if (object.name == options.object) shown = &object;
  }
  if (shown == nullptr) throw std::invalid_argument("no demo object named " + options.object);

  const Connection connection(ToConnectionOptions(options.network));
  for (const SyntheticObject& object : objects) {
    EnrollIfMissing(connection, object, options.save_views);
  }

  std::cout << "\nA device circles " << shown->name << ": " << options.frames
            << " frames from azimuth " << options.start << " in steps of " << options.step
            << " degrees (its compass reads " << options.compass_offset
            << " degrees off; only differences count).\n";
  RecognitionOptions session_options = ToRecognitionOptions(options.session);
  const bool json = options.json;
  session_options.on_update = [json](const v1::SessionUpdate& u) { PrintUpdate(u, json); };
  auto session = RecognitionSession::Open(connection, std::move(session_options));
  for (int k = 0; k < options.frames; ++k) {
    const double azimuth = options.start + k * options.step;
    const cv::Mat frame = RenderView(*shown, azimuth);
    Save(options.save_views, "frame" + std::to_string(k) + ".png", frame);
    session->Push(frame, azimuth + options.compass_offset);
  }
  const grpc::Status status = session->Close();
  if (!status.ok()) throw RpcError("Session", status);
  std::cout
      << "\nEvery frame got the server's ranking, a decision (ACCEPT / UNKNOWN / UNDECIDED)\n"
         "and where to move next. Your own images: orbit enroll --help, orbit recognize --help\n";
  return 0;
}

}  // namespace

void AddDemoCommand(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<DemoOptions>();
  CLI::App* command = app.add_subcommand(
      "demo",
      "See Orbit work without a dataset: renders three textured objects (demo-box, demo-can,\n"
      "demo-crate) from 36 azimuths, enrolls those the server does not hold yet (admin token\n"
      "when the server has tokens), then streams a session around one of them from azimuths\n"
      "it was never shown and prints every update.");
  AddNetworkOptions(*command, options->network, /*server_required=*/true);
  AddSessionFlags(*command, options->session);
  command->add_option("--object", options->object, "the object the device circles")
      ->check(CLI::IsMember({"demo-box", "demo-can", "demo-crate"}))
      ->capture_default_str();
  command->add_option("--start", options->start, "true azimuth of the first frame, degrees")
      ->capture_default_str();
  command->add_option("--step", options->step, "degrees between frames")->capture_default_str();
  command->add_option("--frames", options->frames, "frames to stream")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  command
      ->add_option("--compass-offset", options->compass_offset,
                   "added to every azimuth the device reports")
      ->capture_default_str();
  command->add_option("--save-views", options->save_views,
                      "write the rendered images (enrolled views and frames) to this folder");
  command->add_flag("--json", options->json, "one JSON object per update");
  command->callback([options, &exit_code] { exit_code = RunDemo(*options); });
}

}  // namespace orbit::cli
