#include "cli/session_flags.h"

#include <string>

#include "api/engine_names.h"
#include "core/recognition_engine.h"

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
  command.add_option("--threshold", flags.threshold, "Th: accept when T_M / Ttyp <= Th");
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
  return options;
}

}  // namespace orbit::cli
