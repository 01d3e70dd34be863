// orbit info --server: what a server is and holds (Models.ServerInfo). Also the Docker image's
// health check: exit status 0 only when the server answered.
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "api/conversion.h"
#include "api/engines/conversion.h"
#include "api/engines/engine_names.h"
#include "cli/commands.h"
#include "cli/network_options.h"
#include "cli/rule_estimate_text.h"
#include "cli/session_flags.h"
#include "client/models_client.h"

namespace orbit::cli {
namespace {

struct InfoOptions {
  NetworkOptions network;
  bool json = false;
};

// "calibrated" / "th", as --rejection spells it; "" for a server that does not say.
std::string RejectionText(v1::Rejection rejection) {
  const std::optional<RejectionRule> rule = FromProtoRejection(rejection);
  return rule ? std::string(RejectionRuleName(*rule)) : "";
}

nlohmann::ordered_json InfoJson(const v1::ServerInfoResponse& info) {
  const v1::SessionOptions& d = info.session_defaults();
  const v1::Limits& l = info.limits();
  return {
      {"version", info.version()},
      {"variant", VariantName(FromProtoVariant(info.variant()))},
      {"objects", info.object_count()},
      {"views", info.view_count()},
      {"session_defaults",
       {{"engine", SessionEngineName(d.engine())},
        {"top_k", d.top_k()},
        {"window", d.window()},
        {"w", d.orientation_weight()},
        {"list_length", d.list_length()},
        {"hmm_states", d.hmm_states()},
        {"rejection", RejectionText(d.rejection())},
        {"false_accept_rate", d.false_accept_rate()},
        {"known_accept_rate", d.known_accept_rate()},
        {"threshold", d.threshold()}}},
      {"rule_estimate",
       {{"objects", info.rule_estimate().objects()},
        {"frames", info.rule_estimate().frames()},
        {"unknown_accepted", info.rule_estimate().unknown_accepted()},
        {"known_accepted", info.rule_estimate().known_accepted()},
        {"held_by_known_ceiling", info.rule_estimate().held_by_known_ceiling()}}},
      {"limits",
       {{"max_sessions", l.max_sessions()},
        {"max_frames_per_second", l.max_frames_per_second()},
        {"max_window", l.max_window()},
        {"max_message_bytes", l.max_message_bytes()},
        {"max_views_per_object", l.max_views_per_object()},
        {"idle_timeout_seconds", l.idle_timeout_seconds()},
        {"max_image_pixels", l.max_image_pixels()},
        {"max_hmm_cells", l.max_hmm_cells()},
        {"max_queued_calls", l.max_queued_calls()},
        {"max_sessions_per_token", l.max_sessions_per_token()},
        {"max_recognize_calls_per_token", l.max_recognize_calls_per_token()},
        {"max_enrollments", l.max_enrollments()},
        {"max_enrollment_bytes", l.max_enrollment_bytes()},
        {"enrollment_idle_timeout_seconds", l.enrollment_idle_timeout_seconds()}}},
  };
}

int RunInfo(const InfoOptions& options) {
  const Connection connection(ToConnectionOptions(options.network));
  const v1::ServerInfoResponse response = ModelsClient(connection).ServerInfo();
  const nlohmann::ordered_json info = InfoJson(response);
  if (options.json) {
    std::cout << info.dump() << "\n";
    return 0;
  }
  const auto& d = info["session_defaults"];
  const auto& l = info["limits"];
  std::cout << "server    " << options.network.server << "\n"
            << "version   " << info["version"].get<std::string>() << "\n"
            << "variant   " << info["variant"].get<std::string>() << "\n"
            << "objects   " << info["objects"] << " (" << info["views"] << " views)\n"
            << "defaults  engine " << d["engine"].get<std::string>() << ", top-k " << d["top_k"]
            << ", window " << d["window"] << ", w " << d["w"] << ", N_L " << d["list_length"]
            << ", HMM states " << d["hmm_states"] << ", rejection "
            << d["rejection"].get<std::string>() << " (false-accept rate " << d["false_accept_rate"]
            << ", known-accept rate " << d["known_accept_rate"] << ", threshold " << d["threshold"]
            << ")\n"
            << "limits    " << l["max_sessions"] << " sessions, " << l["max_frames_per_second"]
            << " frames/s per session, window <= " << l["max_window"]
            << ", messages <= " << l["max_message_bytes"] << " bytes, " << l["max_views_per_object"]
            << " views per object, idle timeout " << l["idle_timeout_seconds"]
            << " s, images <= " << l["max_image_pixels"]
            << " pixels, HMM window x states <= " << l["max_hmm_cells"] << "\n"
            << "          " << l["max_queued_calls"] << " calls queued per pool; per token "
            << l["max_sessions_per_token"] << " sessions and " << l["max_recognize_calls_per_token"]
            << " Recognize calls; " << l["max_enrollments"]
            << " enrollments of <= " << l["max_enrollment_bytes"]
            << " bytes, idle <= " << l["enrollment_idle_timeout_seconds"] << " s\n";
  if (response.session_defaults().rejection() == v1::REJECTION_CALIBRATED) {
    std::cout << RuleEstimateText(response.rule_estimate(), response.object_count(),
                                  response.session_defaults().false_accept_rate());
  }
  return 0;
}

}  // namespace

void AddInfoCommand(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<InfoOptions>();
  CLI::App* command = app.add_subcommand(
      "info",
      "Ask a server what it is and holds: version, descriptor variant, object and view counts,\n"
      "session defaults and limits, and how sure the accept / unknown rule can be with the\n"
      "objects enrolled. Exit status 0 when it answered (a health check).");
  AddNetworkOptions(*command, options->network, /*server_required=*/true);
  command->add_flag("--json", options->json, "one JSON object");
  command->callback([options, &exit_code] { exit_code = RunInfo(*options); });
}

}  // namespace orbit::cli
