#include "cli/session_flags.h"

#include <array>
#include <stdexcept>
#include <utility>

namespace orbit::cli {
namespace {

constexpr std::array<std::pair<const char*, v1::Engine>, 8> kEngines = {{
    {"vci", v1::ENGINE_VCI},
    {"hmm", v1::ENGINE_HMM},
    {"vci-hmm", v1::ENGINE_VCI_HMM},
    {"vci-bm", v1::ENGINE_VCI_BM},
    {"vci-w0", v1::ENGINE_VCI_W0},
    {"eis", v1::ENGINE_EIS},
    {"siis", v1::ENGINE_SIIS},
    {"eiis", v1::ENGINE_EIIS},
}};

}  // namespace

std::vector<std::string> EngineFlagNames() {
  std::vector<std::string> names;
  for (const auto& [name, engine] : kEngines) names.emplace_back(name);
  return names;
}

void AddSessionFlags(CLI::App& command, SessionFlags& flags) {
  const std::vector<std::string> names = EngineFlagNames();
  command.add_option("--engine", flags.engine, "recognition method (default: the server's, hmm unless it was started otherwise)")
      ->check(CLI::IsMember(names));
  command.add_option("--top-k", flags.top_k, "candidates per update, 1..100");
  command.add_option("--window", flags.window, "W: frames the session remembers, 1..64");
  command.add_option("--w", flags.orientation_weight,
                     "orientation weight w of the Hough score, per radian");
  command.add_option("--list-length", flags.list_length, "N_L: views per retrieval list");
  command.add_option("--hmm-states", flags.hmm_states, "HMM sectors per object");
  command.add_option("--threshold", flags.threshold, "Th: accept when T_M / Ttyp <= Th");
}

v1::Engine ParseEngine(const std::string& name) {
  for (const auto& [known, engine] : kEngines) {
    if (name == known) return engine;
  }
  throw std::invalid_argument("unknown engine \"" + name + "\"");
}

SessionOptions ToSessionOptions(const SessionFlags& flags) {
  SessionOptions options;
  if (!flags.engine.empty()) options.engine = ParseEngine(flags.engine);
  options.top_k = flags.top_k;
  options.window = flags.window;
  options.orientation_weight = flags.orientation_weight;
  options.list_length = flags.list_length;
  options.hmm_states = flags.hmm_states;
  options.threshold = flags.threshold;
  return options;
}

}  // namespace orbit::cli
