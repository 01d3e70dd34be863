// orbit enroll: enrolls one object on a server from images taken around it, each with its
// azimuth. Descriptors and typical distances are computed here (client/enroller.h).
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/enrollment_report_text.h"
#include "cli/image_arguments.h"
#include "cli/network_options.h"
#include "client/enroller.h"
#include "core/parallel_for.h"

namespace orbit::cli {
namespace {

struct EnrollOptions {
  NetworkOptions network;
  std::string name;
  std::vector<std::string> images;
  std::vector<double> azimuths;
  std::string metadata = "{}";
  std::uint64_t seed = EnrollerOptions{}.seed;
  unsigned threads = static_cast<unsigned>(AvailableCpus());
};

int RunEnroll(const EnrollOptions& options) {
  const std::vector<cv::Mat> pixels = ReadImageArguments(options.images, options.azimuths);
  std::vector<EnrollmentImage> images;
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    images.push_back({pixels[i], options.azimuths[i], {}, {}});
  }
  const Connection connection(ToConnectionOptions(options.network));
  Enroller enroller(connection, {.seed = options.seed, .threads = options.threads});
  const v1::ObjectInfo object = enroller.Enroll(options.name, images, options.metadata);
  std::cout << "enrolled " << object.name() << " (id " << object.id() << ", "
            << object.view_count() << " views)\n"
            << EnrollmentReportText(object.report());
  return 0;
}

}  // namespace

void AddEnrollCommand(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<EnrollOptions>();
  CLI::App* command = app.add_subcommand(
      "enroll",
      "Enroll a new object on a server from images around it: --image F --azimuth A, once per\n"
      "view. Descriptors and typical distances are computed here; the object is stored\n"
      "atomically and recognisable at once. Needs a token with the admin role when the server\n"
      "has tokens.");
  AddNetworkOptions(*command, options->network, /*server_required=*/true);
  command->add_option("--name", options->name, "the new object's unique name")->required();
  command->add_option("--image", options->images, "a view's image file (repeat)")->required();
  command->add_option("--azimuth", options->azimuths,
                      "that view's azimuth in degrees (repeat, in the order of --image)")
      ->required();
  command->add_option("--metadata", options->metadata, "a JSON object stored with the object")
      ->capture_default_str();
  command->add_option("--seed", options->seed,
                      "base seed of the noisy copies for typical distances (the default stores\n"
                      "what a server computes from the same images)")
      ->capture_default_str();
  command->add_option("--threads", options->threads, "threads computing descriptors")
      ->check(CLI::Range(1u, 256u));
  command->callback([options, &exit_code] { exit_code = RunEnroll(*options); });
}

}  // namespace orbit::cli
