// How `orbit recognize` and `orbit demo` print a session update: one line of text, or one JSON
// object (`--json`) with at least frame, decision, move and candidates [{id, name, score}],
// best first.
#pragma once

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "orbit/v1/recognition.pb.h"

namespace orbit::cli {

// "ACCEPT", "UNKNOWN", "UNDECIDED" ("UNSPECIFIED" for a server that left it unset).
std::string_view DecisionText(v1::Decision decision);
// "LEFT", "RIGHT", "NONE" ("UNSPECIFIED" likewise).
std::string_view MoveText(v1::Move move);

// e.g. "frame 3  ACCEPT     move NONE   obj1 (id 1) 0.874, obj7 (id 7) 0.731  [1.2 ms]".
std::string UpdateLine(const v1::SessionUpdate& update);

// {"frame":3,"decision":"ACCEPT","move":"NONE","candidates":[{"id":1,"name":"obj1",
//  "score":0.874},...],"processing_time_us":1234} (and "timestamp_us" when the frame had one).
nlohmann::ordered_json UpdateJson(const v1::SessionUpdate& update);

// Writes UpdateLine or (json) UpdateJson of `update` to stdout and flushes, so a pipe sees each
// update as it arrives.
void PrintUpdate(const v1::SessionUpdate& update, bool json);

}  // namespace orbit::cli
