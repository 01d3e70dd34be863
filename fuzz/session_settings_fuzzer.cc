// Fuzz target: the options a device opens a session with, resolved as the server resolves them
// (server/session_settings.h, ResolveSessionSettings) against the defaults and limits of
// `orbit serve`, for each descriptor variant.
//
// Input: a serialized orbit.v1.SessionOptions; bytes that do not parse are skipped.
//
// Checked beyond "no crash", for options the server admits: every option is in its documented
// range and within the limits (the HMM memory rule included); ServerInfo's account of them
// (DescribeSettings) resolves back to the same settings; and the session's engine can be built
// from them.
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "api/engines/engine_names.h"
#include "core/engines/recognition_engine.h"
#include "fuzz/fuzz_support.h"
#include "orbit/v1/recognition.pb.h"
#include "server/session_engine.h"
#include "server/session_settings.h"

namespace {

bool SameSettings(const orbit::server::SessionSettings& a,
                  const orbit::server::SessionSettings& b) {
  const orbit::EngineOptions &x = a.options, &y = b.options;
  return a.engine == b.engine && x.window == y.window && x.list_length == y.list_length &&
         x.orientation_weight == y.orientation_weight && x.hmm_states == y.hmm_states &&
         x.threshold == y.threshold && x.top_k == y.top_k && x.averaged_views == y.averaged_views &&
         x.ambiguity_margin == y.ambiguity_margin;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace orbit;
  static const server::ServerLimits limits = fuzz::FuzzLimits();
  static const server::SessionSettings defaults;

  fuzz::SilenceProtobufLogs();
  v1::SessionOptions requested;
  if (!requested.ParseFromArray(data, static_cast<int>(size))) return 0;
  for (const DescriptorVariant variant : kDescriptorVariants) {
    server::SessionSettings settings;
    if (!server::ResolveSessionSettings(requested, defaults, variant, limits, &settings).ok()) {
      continue;
    }
    const EngineOptions& o = settings.options;
    ORBIT_FUZZ_CHECK(!SessionEngineName(settings.engine).empty());
    ORBIT_FUZZ_CHECK(o.top_k >= 1 && o.top_k <= 100);
    ORBIT_FUZZ_CHECK(o.window >= 1 && o.window <= limits.max_window);
    ORBIT_FUZZ_CHECK(o.list_length >= 1 && o.list_length <= 64);
    ORBIT_FUZZ_CHECK(o.hmm_states >= 1 && o.hmm_states <= kMaxHmmStates);
    ORBIT_FUZZ_CHECK(std::isfinite(o.orientation_weight) && o.orientation_weight >= 0);
    ORBIT_FUZZ_CHECK(std::isfinite(o.threshold) && o.threshold > 0);
    ORBIT_FUZZ_CHECK(server::CheckHmmCells(settings, limits).ok());

    server::SessionSettings again;
    ORBIT_FUZZ_CHECK(server::ResolveSessionSettings(server::DescribeSettings(settings, variant),
                                                    defaults, variant, limits, &again)
                         .ok());
    ORBIT_FUZZ_CHECK(SameSettings(settings, again));

    server::CreateSessionEngine(settings)->Reset();
  }
  return 0;
}
