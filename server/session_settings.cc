#include "server/session_settings.h"

#include <optional>
#include <stdexcept>
#include <string>

#include "api/conversion.h"
#include "api/engines/conversion.h"
#include "api/engines/engine_names.h"
#include "server/error_status.h"
#include "server/request_reading.h"

namespace orbit::server {

grpc::Status CheckHmmCells(const SessionSettings& settings, const ServerLimits& limits) {
  const EngineOptions& o = settings.options;
  if (RunsHmm(settings.engine) && o.window * o.hmm_states > limits.max_hmm_cells) {
    return {grpc::StatusCode::RESOURCE_EXHAUSTED,
            "options.window x options.hmm_states = " + std::to_string(o.window) + " x " +
                std::to_string(o.hmm_states) + " is above this server's " +
                std::to_string(limits.max_hmm_cells) +
                " (the HMM keeps window x states values per object)"};
  }
  return grpc::Status::OK;
}

grpc::Status ResolveSessionSettings(const v1::SessionOptions& requested,
                                    const SessionSettings& defaults, DescriptorVariant variant,
                                    const ServerLimits& limits, SessionSettings* out) {
  if (auto s = CheckVariant(requested.variant(), variant, "options.variant"); !s.ok()) return s;
  SessionSettings settings = defaults;
  if (requested.engine() != v1::ENGINE_UNSPECIFIED) {
    if (SessionEngineName(requested.engine()).empty()) {
      return InvalidArgument("options.engine " + std::to_string(requested.engine()) +
                             " is not an engine");
    }
    settings.engine = requested.engine();
  }
  if (requested.rejection() != v1::REJECTION_UNSPECIFIED) {
    const std::optional<RejectionRule> rule = FromProtoRejection(requested.rejection());
    if (!rule) {
      return InvalidArgument("options.rejection " + std::to_string(requested.rejection()) +
                             " is not a rule (REJECTION_TH = 1, REJECTION_CALIBRATED = 2)");
    }
    settings.options.rejection = *rule;
  }
  // A field at 0 or unset keeps the default; every value is checked below, once.
  EngineOptions& o = settings.options;
  if (requested.top_k() != 0) o.top_k = requested.top_k();
  if (requested.window() != 0) o.window = requested.window();
  if (requested.has_orientation_weight()) o.orientation_weight = requested.orientation_weight();
  if (requested.list_length() != 0) o.list_length = requested.list_length();
  if (requested.hmm_states() != 0) o.hmm_states = requested.hmm_states();
  if (requested.has_threshold()) o.threshold = requested.threshold();
  if (requested.has_false_accept_rate()) o.false_accept_rate = requested.false_accept_rate();
  if (requested.has_known_accept_rate()) o.known_accept_rate = requested.known_accept_rate();
  try {
    ValidateEngineOptions(o, "options.");
  } catch (const std::invalid_argument& e) {
    return InvalidArgument(e.what());
  }
  // Within the API's ranges, above what this server allows.
  if (o.window > limits.max_window) {
    return {grpc::StatusCode::RESOURCE_EXHAUSTED, "options.window " + std::to_string(o.window) +
                                                      " is above this server's " +
                                                      std::to_string(limits.max_window)};
  }
  if (auto s = CheckHmmCells(settings, limits); !s.ok()) return s;
  *out = settings;
  return grpc::Status::OK;
}

v1::SessionOptions DescribeSettings(const SessionSettings& settings, DescriptorVariant variant) {
  v1::SessionOptions o;
  o.set_engine(settings.engine);
  o.set_top_k(settings.options.top_k);
  o.set_window(settings.options.window);
  o.set_orientation_weight(settings.options.orientation_weight);
  o.set_list_length(settings.options.list_length);
  o.set_hmm_states(settings.options.hmm_states);
  o.set_threshold(settings.options.threshold);
  o.set_rejection(ToProtoRejection(settings.options.rejection));
  o.set_false_accept_rate(settings.options.false_accept_rate);
  o.set_known_accept_rate(settings.options.known_accept_rate);
  o.set_variant(ToProtoVariant(variant));
  return o;
}

}  // namespace orbit::server
