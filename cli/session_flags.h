// The session options of `orbit recognize` and `orbit demo` as command-line flags
// (--engine, --top-k, --window, --w, --list-length, --hmm-states, --rejection, --false-accept-rate,
// --known-accept-rate, --threshold); a flag left out takes the server's default. Engine names
// are api/engines/engine_names.h's.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "client/recognition_session.h"

namespace orbit::cli {

// The flags bind to the client's options directly; only the two named by text are parsed after.
struct SessionFlags {
  RecognitionOptions options;
  std::string engine;     // "" for the server's default
  std::string rejection;  // "calibrated", "th" or "" (the server's)
};

void AddSessionFlags(CLI::App& command, SessionFlags& flags);

RecognitionOptions ToRecognitionOptions(const SessionFlags& flags);

}  // namespace orbit::cli
