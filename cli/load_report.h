// LoadReport: what one run of `orbit loadtest` measured, and its two renderings: a text summary
// for people and one JSON object (--json) for scripts (scripts/loadtest.sh builds the table of
// docs/results/load.md from it).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/latency_histogram.h"
#include "cli/process_usage.h"

namespace orbit {

struct LoadReport {
  // What was asked.
  std::string server;          // HOST:PORT
  std::string engine;          // the sessions' engine (api/engines/engine_names.h)
  int sessions = 0;            // sessions asked for
  int connections = 1;         // TCP connections they share (round robin)
  std::optional<double> rate;  // frames/s per session (open loop); unset: closed loop
  double duration_seconds = 0;
  bool image_frames = false;  // encoded images instead of descriptors

  // What happened. Every duration is in microseconds.
  double elapsed_seconds = 0;  // the duration, or until the last update if that came later
  int sessions_opened = 0;     // sessions that received at least one update
  int sessions_failed = 0;     // sessions refused, or ended with a status other than OK
  int sessions_cancelled = 0;  // still owed updates when the generator stopped waiting
  std::uint64_t frames_sent = 0;
  std::uint64_t frames_answered = 0;
  // Round trip of every answered frame: from its scheduled send time (open loop, so a frame
  // the generator or a queue delayed counts its wait) or its send (closed loop) to its update.
  LatencyHistogram round_trip;
  // The largest p99 of one session's round trips, and how many sessions had a p99 above 5 ms:
  // a soak's "no session's p99 above 5 ms" is read from these, not from the pooled p99.
  double worst_session_p99_us = 0;
  int sessions_p99_above_5ms = 0;
  LatencyHistogram processing;  // the updates' processing_time_us (the server's own figure)
  // Calls that ended with a status other than OK, by status name ("RESOURCE_EXHAUSTED"):
  // session streams, enrollments and deletions.
  std::map<std::string, std::uint64_t> errors;

  // Enrollments run during the load (--enroll-every, --enroll-count).
  bool enrollments_run = false;  // whether enrollments were asked for
  int enrollments_done = 0;
  int enrollments_deleted = 0;  // during the load (--delete-during) or after it
  bool deleted_during = false;  // --delete-during
  int enrollment_views = 0;
  LatencyHistogram enrollment;            // per successful enrollment call
  LatencyHistogram round_trip_enrolling;  // frames sent or answered while one ran

  // The server process (--server-pid): at the first frame and after the last update, and its
  // resident memory every tenth of the load (seconds from the first frame, bytes), so that a
  // soak shows whether memory stays flat after the warm-up.
  std::optional<ProcessUsage> server_start;
  std::optional<ProcessUsage> server_end;
  std::vector<std::pair<double, std::int64_t>> server_rss_samples;
  // The generator's own CPU time over the same span.
  double generator_cpu_seconds = 0;

  double FramesPerSecond() const;
};

// {"frames_per_second", "rtt_ms": {p50, p90, p99, max, mean}, "errors": {NAME: count},
//  "sessions": {...}, "frames": {...}, "server": {...}, "generator": {...}, "enrollments": {...},
//  "config": {...}}; docs/results/load.md lists every field.
nlohmann::ordered_json LoadReportJson(const LoadReport& report);

// The same as a few lines of text for a terminal.
std::string LoadReportText(const LoadReport& report);

}  // namespace orbit
