// The session options of `orbit recognize` and `orbit demo` as command-line flags
// (--engine, --top-k, --window, --w, --list-length, --hmm-states, --rejection, --false-accept-rate, --threshold); a flag left out
// takes the server's default. Engine names are api/engine_names.h's.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "client/recognition_session.h"

namespace orbit::cli {

struct SessionFlags {
  std::string engine;  // "" for the server's default
  int top_k = 0;
  int window = 0;
  std::optional<double> orientation_weight;
  int list_length = 0;
  int hmm_states = 0;
  std::optional<double> threshold;
  std::string rejection;  // "calibrated", "th" or "" (the server's)
  std::optional<double> false_accept_rate;
};

void AddSessionFlags(CLI::App& command, SessionFlags& flags);

SessionOptions ToSessionOptions(const SessionFlags& flags);

}  // namespace orbit::cli
