#include "cli/session_flags.h"

#include <string>

#include "api/engines/conversion.h"
#include "api/engines/engine_names.h"
#include "core/engines/engine_options.h"

namespace orbit::cli {

void AddSessionFlags(CLI::App& command, SessionFlags& flags) {
  command
      .add_option("--engine", flags.engine,
                  "recognition method (default: the server's, hmm unless it was started "
                  "otherwise)")
      ->check(CLI::IsMember(SessionEngineNames()));
  command.add_option("--top-k", flags.options.top_k,
                     "candidates per update, 1.." + std::to_string(kMaxTopK));
  command.add_option("--window", flags.options.window,
                     "W: frames the session remembers, 1.." + std::to_string(kMaxWindow));
  command.add_option("--w", flags.options.orientation_weight,
                     "orientation weight w of the Hough score, per radian, 0.." +
                         std::to_string(static_cast<int>(kMaxOrientationWeight)));
  command.add_option("--list-length", flags.options.list_length,
                     "N_L: views per retrieval list, 1.." + std::to_string(kMaxListLength));
  command.add_option("--hmm-states", flags.options.hmm_states,
                     "HMM sectors per object, 1.." + std::to_string(kMaxHmmStates));
  command
      .add_option("--rejection", flags.rejection,
                  "accept / unknown rule: calibrated (a threshold from --false-accept-rate, "
                  "computed by the server from its model set) or th (the thesis' rule in "
                  "docs/design.md, --threshold)")
      ->check(CLI::IsMember({"calibrated", "th"}));
  command
      .add_option("--false-accept-rate", flags.options.false_accept_rate,
                  "the calibrated rule's target share of unknown objects accepted, in (0, 1)")
      ->check(CLI::Range(1e-6, 1 - 1e-6));
  command
      .add_option("--known-accept-rate", flags.options.known_accept_rate,
                  "the calibrated rule's known share: where the enrolled objects look alike, the "
                  "threshold is raised until this share of their own windows is accepted, in "
                  "[0, 1); 0: the target rate alone")
      ->check(CLI::Range(0.0, 1 - 1e-6));
  command.add_option("--threshold", flags.options.threshold,
                     "Th of the th rule: accept when T_M / Ttyp <= Th");
}

RecognitionOptions ToRecognitionOptions(const SessionFlags& flags) {
  RecognitionOptions options = flags.options;
  if (!flags.engine.empty()) options.engine = ParseSessionEngine(flags.engine);
  if (!flags.rejection.empty()) {
    options.rejection = ToProtoRejection(ParseRejectionRule(flags.rejection));
  }
  return options;
}

}  // namespace orbit::cli
