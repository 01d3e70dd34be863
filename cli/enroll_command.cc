// orbit enroll: enrolls one object on a server from images taken around it, each with its
// azimuth, or from a video of a walk around it with the walk's orientation log (docs/capture.md).
// Descriptors and typical distances are computed here (client/enroller.h).
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/box_arguments.h"
#include "cli/capture_arguments.h"
#include "cli/capture_selection_text.h"
#include "cli/commands.h"
#include "cli/enrollment_report_text.h"
#include "cli/image_arguments.h"
#include "cli/network_options.h"
#include "cli/rule_estimate_text.h"
#include "client/capture_views.h"
#include "client/enroller.h"
#include "client/models_client.h"
#include "core/base/parallel_for.h"

namespace orbit::cli {
namespace {

struct EnrollOptions {
  NetworkOptions network;
  std::string name;
  std::vector<std::string> images;
  std::vector<double> azimuths;
  BoxArguments boxes;
  CaptureArguments capture;
  double step = kDefaultEnrollmentStepDeg;
  std::string metadata = "{}";
  std::uint64_t seed = EnrollerOptions{}.seed;
  unsigned threads = static_cast<unsigned>(AvailableCpus());
};

// The server's accept / unknown rule with the object just enrolled, when it runs the calibrated
// one ("" otherwise).
std::string RuleText(const Connection& connection) {
  const v1::ServerInfoResponse info = ModelsClient(connection).ServerInfo();
  if (info.session_defaults().rejection() != v1::REJECTION_CALIBRATED) return "";
  return RuleEstimateText(info.rule_estimate(), info.object_count(),
                          info.session_defaults().false_accept_rate());
}

int RunEnrollFromVideo(const EnrollOptions& options) {
  const std::unique_ptr<CaptureReader> capture = OpenCapture(options.capture, options.boxes);
  const Connection connection(ToConnectionOptions(options.network));
  Enroller enroller(connection, {.seed = options.seed, .threads = options.threads});
  const Enroller::VideoEnrollment enrolled = enroller.FromVideo(
      options.name, *capture, {.step_deg = options.step, .progress = CaptureProgress()},
      options.metadata);
  const v1::ObjectInfo& object = enrolled.object;
  std::cout << "enrolled " << object.name() << " (id " << object.id() << ", " << object.view_count()
            << " views)\n"
            << CaptureSelectionText(enrolled.selection, options.step)
            << EnrollmentReportText(object.report()) << RuleText(connection);
  return 0;
}

int RunEnroll(const EnrollOptions& options) {
  if (!options.capture.video.empty()) {
    if (!options.images.empty() || !options.azimuths.empty()) {
      throw std::invalid_argument("give --video or --image, not both");
    }
    return RunEnrollFromVideo(options);
  }
  if (options.images.empty()) throw std::invalid_argument("give --image F --azimuth A, or --video");
  // Every image is read and every box checked before the server is called: a bad one enrolls
  // nothing.
  const std::vector<cv::Mat> pixels =
      ReadImageArguments(options.images, options.azimuths, AzimuthArguments::kOnePerImage);
  const std::vector<std::optional<cv::Rect>> regions =
      ImageRegions(options.boxes, options.images, pixels);
  std::vector<EnrollmentImage> images;
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    images.push_back({pixels[i], options.azimuths[i], regions[i], {}});
  }
  const Connection connection(ToConnectionOptions(options.network));
  Enroller enroller(connection, {.seed = options.seed, .threads = options.threads});
  const v1::ObjectInfo object = enroller.Enroll(options.name, images, options.metadata);
  std::cout << "enrolled " << object.name() << " (id " << object.id() << ", " << object.view_count()
            << " views)\n"
            << EnrollmentReportText(object.report()) << RuleText(connection);
  return 0;
}

}  // namespace

void AddEnrollCommand(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<EnrollOptions>();
  CLI::App* command = app.add_subcommand(
      "enroll",
      "Enroll a new object on a server from images around it: --image F --azimuth A, once per\n"
      "view, and where the object is in each (--box x,y,w,h once per --image, or --boxes\n"
      "boxes.csv; grown by --box-margin; default: the whole image); or from a video of a walk\n"
      "around it: --video V --orientation LOG [--box x,y,w,h on the first frame], which keeps\n"
      "the sharpest frame of every --step degrees of azimuth. Descriptors and\n"
      "typical distances are computed here; the object is stored atomically and recognisable\n"
      "at once. Needs a token with the admin role when the server has tokens.");
  AddNetworkOptions(*command, options->network, /*server_required=*/true);
  command->add_option("--name", options->name, "the new object's unique name")->required();
  command->add_option("--image", options->images, "a view's image file (repeat)");
  command->add_option("--azimuth", options->azimuths,
                      "that view's azimuth in degrees (repeat, in the order of --image)");
  AddCaptureOptions(*command, options->capture);
  AddBoxOptions(*command, options->boxes);
  command
      ->add_option("--step", options->step,
                   "with --video: one view per this many degrees of azimuth; the frame kept "
                   "in each step, or why none was, and the arcs between views wider than a "
                   "step are printed")
      ->capture_default_str()
      ->check(CLI::Range(0.5, 180.0));
  command->add_option("--metadata", options->metadata, "a JSON object stored with the object")
      ->capture_default_str();
  command
      ->add_option("--seed", options->seed,
                   "base seed of the noisy copies for typical distances (the default stores\n"
                   "what a server computes from the same images)")
      ->capture_default_str();
  command->add_option("--threads", options->threads, "threads computing descriptors")
      ->check(CLI::Range(1u, 256u));
  command->callback([options, &exit_code] { exit_code = RunEnroll(*options); });
}

}  // namespace orbit::cli
