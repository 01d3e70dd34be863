#include "server/session_settings.h"

#include <cmath>
#include <string>

#include "server/api_conversion.h"

namespace orbit::server {
namespace {

constexpr int kMaxTopK = 100;
constexpr int kMaxListLength = 64;

grpc::Status Invalid(const std::string& message) {
  return {grpc::StatusCode::INVALID_ARGUMENT, message};
}

}  // namespace

std::vector<std::string_view> CoreEngineNames(v1::Engine engine) {
  switch (engine) {
    case v1::ENGINE_VCI:
      return {"vci"};
    case v1::ENGINE_HMM:
      return {"hmm"};
    case v1::ENGINE_VCI_HMM:
      return {"vci", "hmm"};
    case v1::ENGINE_VCI_BM:
      return {"vci-bm"};
    case v1::ENGINE_VCI_W0:
      return {"vci-w0"};
    case v1::ENGINE_EIS:
      return {"eis"};
    case v1::ENGINE_SIIS:
      return {"siis"};
    case v1::ENGINE_EIIS:
      return {"eiis"};
    default:
      return {};
  }
}

bool RunsHmm(v1::Engine engine) {
  return engine == v1::ENGINE_HMM || engine == v1::ENGINE_VCI_HMM;
}

grpc::Status ResolveSessionSettings(const v1::SessionOptions& requested,
                                    const SessionSettings& defaults, DescriptorVariant variant,
                                    const ServerLimits& limits, SessionSettings* out) {
  if (auto s = CheckVariant(requested.variant(), variant, "options.variant"); !s.ok()) return s;
  SessionSettings settings = defaults;
  if (requested.engine() != v1::ENGINE_UNSPECIFIED) {
    if (CoreEngineNames(requested.engine()).empty()) {
      return Invalid("options.engine " + std::to_string(requested.engine()) + " is not an engine");
    }
    settings.engine = requested.engine();
  }
  EngineOptions& o = settings.options;
  if (requested.top_k() != 0) {
    if (requested.top_k() < 1 || requested.top_k() > kMaxTopK) {
      return Invalid("options.top_k must be 1..100");
    }
    o.top_k = requested.top_k();
  }
  if (requested.window() != 0) {
    if (requested.window() < 1) return Invalid("options.window must be at least 1");
    if (requested.window() > limits.max_window) {
      return {grpc::StatusCode::RESOURCE_EXHAUSTED,
              "options.window " + std::to_string(requested.window()) + " is above this server's " +
                  std::to_string(limits.max_window)};
    }
    o.window = requested.window();
  }
  if (requested.has_orientation_weight()) {
    const double w = requested.orientation_weight();
    if (!std::isfinite(w) || w < 0) return Invalid("options.orientation_weight must be >= 0");
    o.orientation_weight = w;
  }
  if (requested.list_length() != 0) {
    if (requested.list_length() < 1 || requested.list_length() > kMaxListLength) {
      return Invalid("options.list_length must be 1..64");
    }
    o.list_length = requested.list_length();
  }
  if (requested.hmm_states() != 0) {
    if (requested.hmm_states() < 1 || requested.hmm_states() > 360) {
      return Invalid("options.hmm_states must be 1..360");
    }
    o.hmm_states = requested.hmm_states();
  }
  if (requested.has_threshold()) {
    const double th = requested.threshold();
    if (!std::isfinite(th) || th <= 0) return Invalid("options.threshold must be > 0");
    o.threshold = th;
  }
  if (RunsHmm(settings.engine) && o.window * o.hmm_states > limits.max_hmm_cells) {
    return {grpc::StatusCode::RESOURCE_EXHAUSTED,
            "options.window x options.hmm_states = " + std::to_string(o.window) + " x " +
                std::to_string(o.hmm_states) + " is above this server's " +
                std::to_string(limits.max_hmm_cells) +
                " (the HMM keeps window x states values per object)"};
  }
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
  o.set_variant(ToProto(variant));
  return o;
}

}  // namespace orbit::server
