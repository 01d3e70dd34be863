#include "cli/update_format.h"

#include <cstdio>
#include <iostream>

namespace orbit::cli {

std::string_view DecisionText(v1::Decision decision) {
  switch (decision) {
    case v1::DECISION_ACCEPT: return "ACCEPT";
    case v1::DECISION_UNKNOWN: return "UNKNOWN";
    case v1::DECISION_UNDECIDED: return "UNDECIDED";
    default: return "UNSPECIFIED";
  }
}

std::string_view MoveText(v1::Move move) {
  switch (move) {
    case v1::MOVE_NONE: return "NONE";
    case v1::MOVE_LEFT: return "LEFT";
    case v1::MOVE_RIGHT: return "RIGHT";
    default: return "UNSPECIFIED";
  }
}

std::string UpdateLine(const v1::SessionUpdate& update) {
  char head[160];
  std::snprintf(head, sizeof head, "frame %lld  %-9s  confidence %.2f  move %-5s ",
                static_cast<long long>(update.frame_index()),
                std::string(DecisionText(update.decision())).c_str(), update.confidence(),
                std::string(MoveText(update.move())).c_str());
  std::string line = head;
  if (update.has_pose()) {
    char pose[64];
    std::snprintf(pose, sizeof pose, " seen from %.0f deg (+-%.0f) ", update.pose().azimuth_deg(),
                  update.pose().spread_deg());
    line += pose;
  }
  if (update.candidates().empty()) line += " (no objects)";
  for (int i = 0; i < update.candidates_size(); ++i) {
    const v1::Candidate& c = update.candidates(i);
    char candidate[64];
    std::snprintf(candidate, sizeof candidate, " (id %lld) %.3f", static_cast<long long>(c.id()),
                  c.score());
    line += (i == 0 ? " " : ", ") + c.name() + candidate;
  }
  char time[32];
  std::snprintf(time, sizeof time, "  [%.1f ms]", update.processing_time_us() / 1000.0);
  return line + time;
}

nlohmann::ordered_json UpdateJson(const v1::SessionUpdate& update) {
  nlohmann::ordered_json candidates = nlohmann::ordered_json::array();
  for (const v1::Candidate& c : update.candidates()) {
    candidates.push_back({{"id", c.id()}, {"name", c.name()}, {"score", c.score()}});
  }
  nlohmann::ordered_json line = {
      {"frame", update.frame_index()},       {"decision", DecisionText(update.decision())},
      {"confidence", update.confidence()},   {"move", MoveText(update.move())},
      {"candidates", std::move(candidates)}, {"processing_time_us", update.processing_time_us()},
  };
  if (update.has_pose()) {
    line["pose"] = {{"azimuth_deg", update.pose().azimuth_deg()},
                    {"spread_deg", update.pose().spread_deg()}};
  }
  if (update.has_timestamp_us()) line["timestamp_us"] = update.timestamp_us();
  return line;
}

void PrintUpdate(const v1::SessionUpdate& update, bool json) {
  std::cout << (json ? UpdateJson(update).dump() : UpdateLine(update)) << std::endl;
}

}  // namespace orbit::cli
