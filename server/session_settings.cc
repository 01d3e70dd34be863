#include "server/session_settings.h"

#include <cmath>
#include <string>

#include "api/conversion.h"
#include "api/engine_names.h"
#include "server/error_status.h"
#include "server/request_reading.h"

namespace orbit::server {
namespace {

constexpr int kMaxTopK = 100;
constexpr int kMaxListLength = 64;

}  // namespace

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
    if (CoreEngineNames(requested.engine()).empty()) {
      return InvalidArgument("options.engine " + std::to_string(requested.engine()) +
                             " is not an engine");
    }
    settings.engine = requested.engine();
  }
  EngineOptions& o = settings.options;
  if (requested.top_k() != 0) {
    if (requested.top_k() < 1 || requested.top_k() > kMaxTopK) {
      return InvalidArgument("options.top_k must be 1.." + std::to_string(kMaxTopK));
    }
    o.top_k = requested.top_k();
  }
  if (requested.window() != 0) {
    if (requested.window() < 1 || requested.window() > kMaxWindow) {
      return InvalidArgument("options.window must be 1.." + std::to_string(kMaxWindow));
    }
    if (requested.window() > limits.max_window) {
      return {grpc::StatusCode::RESOURCE_EXHAUSTED,
              "options.window " + std::to_string(requested.window()) + " is above this server's " +
                  std::to_string(limits.max_window)};
    }
    o.window = requested.window();
  }
  if (requested.has_orientation_weight()) {
    const double w = requested.orientation_weight();
    if (!(w >= 0 && w <= kMaxOrientationWeight)) {  // NaN fails both comparisons
      return InvalidArgument("options.orientation_weight must be in [0, " +
                             std::to_string(static_cast<int>(kMaxOrientationWeight)) + "]");
    }
    o.orientation_weight = w;
  }
  if (requested.list_length() != 0) {
    if (requested.list_length() < 1 || requested.list_length() > kMaxListLength) {
      return InvalidArgument("options.list_length must be 1.." + std::to_string(kMaxListLength));
    }
    o.list_length = requested.list_length();
  }
  if (requested.hmm_states() != 0) {
    if (requested.hmm_states() < 1 || requested.hmm_states() > kMaxHmmStates) {
      return InvalidArgument("options.hmm_states must be 1.." + std::to_string(kMaxHmmStates));
    }
    o.hmm_states = requested.hmm_states();
  }
  if (requested.has_threshold()) {
    const double th = requested.threshold();
    if (!std::isfinite(th) || th <= 0) return InvalidArgument("options.threshold must be > 0");
    o.threshold = th;
  }
  if (requested.rejection() != v1::REJECTION_UNSPECIFIED) {
    const std::optional<RejectionRule> rule = FromProtoRejection(requested.rejection());
    if (!rule) {
      return InvalidArgument("options.rejection " + std::to_string(requested.rejection()) +
                             " is not a rule (REJECTION_TH = 1, REJECTION_CALIBRATED = 2)");
    }
    o.rejection = *rule;
  }
  if (requested.has_false_accept_rate()) {
    const double rate = requested.false_accept_rate();
    if (!(rate > 0 && rate < 1)) {
      return InvalidArgument("options.false_accept_rate must be in (0, 1)");
    }
    o.false_accept_rate = rate;
  }
  if (auto s = CheckHmmCells(settings, limits); !s.ok()) return s;
  try {
    ValidateEngineOptions(o);
  } catch (const std::exception& e) {
    return StatusFromException(e);
  }
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
  o.set_variant(ToProtoVariant(variant));
  return o;
}

}  // namespace orbit::server
