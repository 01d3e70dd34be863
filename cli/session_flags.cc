#include "cli/session_flags.h"

#include <string>

#include "api/conversion.h"
#include "api/engine_names.h"
#include "core/engines/recognition_engine.h"

namespace orbit::cli {

void AddSessionFlags(CLI::App& command, SessionFlags& flags) {
  command.add_option("--engine", flags.engine,
                     "recognition method (default: the server's, hmm unless it was started "
                     "otherwise)")
      ->check(CLI::IsMember(SessionEngineNames()));
  command.add_option("--top-k", flags.top_k, "candidates per update, 1..100");
  command.add_option("--window", flags.window,
                     "W: frames the session remembers, 1.." + std::to_string(kMaxWindow));
  command.add_option("--w", flags.orientation_weight,
                     "orientation weight w of the Hough score, per radian, 0.." +
                         std::to_string(static_cast<int>(kMaxOrientationWeight)));
  command.add_option("--list-length", flags.list_length, "N_L: views per retrieval list");
  command.add_option("--hmm-states", flags.hmm_states, "HMM sectors per object");
  command.add_option("--rejection", flags.rejection,
                     "accept / unknown rule: calibrated (a threshold from --false-accept-rate, "
                     "computed by the server from its model set) or th (the thesis' rule in "
                     "docs/design.md, --threshold)")
      ->check(CLI::IsMember({"calibrated", "th"}));
  command.add_option("--false-accept-rate", flags.false_accept_rate,
                     "the calibrated rule's target share of unknown objects accepted, in (0, 1)")
      ->check(CLI::Range(1e-6, 1 - 1e-6));
  command.add_option("--threshold", flags.threshold, "Th of the th rule: accept when T_M / Ttyp <= Th");
}

SessionOptions ToSessionOptions(const SessionFlags& flags) {
  SessionOptions options;
  if (!flags.engine.empty()) options.engine = ParseSessionEngine(flags.engine);
  options.top_k = flags.top_k;
  options.window = flags.window;
  options.orientation_weight = flags.orientation_weight;
  options.list_length = flags.list_length;
  options.hmm_states = flags.hmm_states;
  options.threshold = flags.threshold;
  if (!flags.rejection.empty()) {
    options.rejection = ToProtoRejection(ParseRejectionRule(flags.rejection));
  }
  options.false_accept_rate = flags.false_accept_rate;
  return options;
}

}  // namespace orbit::cli
