#include "cli/load_report.h"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace orbit {
namespace {

using Json = nlohmann::ordered_json;

// `value` to `decimals` places, divided last so that JSON prints 160.2, not 160.20000000000002.
double Rounded(double value, int decimals) {
  const double scale = std::pow(10.0, decimals);
  return std::round(value * scale) / scale;
}

// Milliseconds to the microsecond, from microseconds.
double Ms(double microseconds) { return std::round(microseconds) / 1000.0; }

Json RoundTripJson(const LatencyHistogram& h) {
  return Json{{"p50", Ms(h.Percentile(50))}, {"p90", Ms(h.Percentile(90))},
              {"p99", Ms(h.Percentile(99))}, {"max", Ms(static_cast<double>(h.max()))},
              {"mean", Ms(h.mean())},        {"count", h.count()}};
}

double Megabytes(std::int64_t bytes) { return Rounded(bytes / 1048576.0, 1); }

// CPU seconds over the report's span, per answered frame and as a share of one core.
Json CpuJson(double cpu_seconds, const LoadReport& report) {
  Json cpu{{"cpu_seconds", Rounded(cpu_seconds, 3)}};
  cpu["cpu_us_per_frame"] =
      report.frames_answered ? Rounded(cpu_seconds * 1e6 / report.frames_answered, 1) : 0.0;
  cpu["cpu_percent"] =
      report.elapsed_seconds > 0 ? Rounded(100 * cpu_seconds / report.elapsed_seconds, 1) : 0.0;
  return cpu;
}

std::string Format(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

}  // namespace

double LoadReport::FramesPerSecond() const {
  return elapsed_seconds > 0 ? frames_answered / elapsed_seconds : 0;
}

Json LoadReportJson(const LoadReport& report) {
  Json config{{"server", report.server},
              {"engine", report.engine},
              {"sessions", report.sessions},
              {"connections", report.connections},
              {"mode", report.rate ? "open-loop" : "closed-loop"}};
  if (report.rate) config["rate_per_session"] = *report.rate;
  config["duration_s"] = report.duration_seconds;
  config["frames"] = report.image_frames ? "image" : "descriptor";

  Json json;
  json["config"] = config;
  json["frames_per_second"] = Rounded(report.FramesPerSecond(), 1);
  json["rtt_ms"] = RoundTripJson(report.round_trip);
  json["rtt_ms"]["worst_session_p99"] = Ms(report.worst_session_p99_us);
  json["rtt_ms"]["sessions_p99_above_5ms"] = report.sessions_p99_above_5ms;
  json["errors"] = Json::object();
  for (const auto& [name, count] : report.errors) json["errors"][name] = count;
  json["sessions"] = {{"asked", report.sessions},
                      {"opened", report.sessions_opened},
                      {"failed", report.sessions_failed},
                      {"cancelled", report.sessions_cancelled}};
  json["frames"] = {{"sent", report.frames_sent},
                    {"answered", report.frames_answered},
                    {"unanswered", report.frames_sent - report.frames_answered}};
  json["elapsed_s"] = Rounded(report.elapsed_seconds, 3);

  Json server{{"processing_time_us",
               {{"p50", Rounded(report.processing.Percentile(50), 0)},
                {"p99", Rounded(report.processing.Percentile(99), 0)},
                {"max", report.processing.max()}}}};
  if (report.server_start && report.server_end) {
    server.update(
        CpuJson(report.server_end->cpu_seconds - report.server_start->cpu_seconds, report));
    server["rss_mb_start"] = Megabytes(report.server_start->rss_bytes);
    server["rss_mb_end"] = Megabytes(report.server_end->rss_bytes);
  }
  if (!report.server_rss_samples.empty()) {
    Json samples = Json::array();
    for (const auto& [seconds, bytes] : report.server_rss_samples) {
      samples.push_back({Rounded(seconds, 1), Megabytes(bytes)});
    }
    server["rss_mb_samples"] = samples;  // [[seconds since the first frame, MB], ...]
  }
  json["server"] = server;
  json["generator"] = CpuJson(report.generator_cpu_seconds, report);

  if (report.enrollments_run) {
    const LatencyHistogram& e = report.enrollment;
    json["enrollments"] = {
        {"done", report.enrollments_done},
        {"deleted", report.enrollments_deleted},
        {"deleted_during_load", report.deleted_during},
        {"views", report.enrollment_views},
        {"latency_ms",
         {{"p50", Ms(e.Percentile(50))}, {"p99", Ms(e.Percentile(99))}, {"max", Ms(e.max())}}},
        {"rtt_ms_during", RoundTripJson(report.round_trip_enrolling)}};
  }
  return json;
}

std::string LoadReportText(const LoadReport& report) {
  std::ostringstream out;
  const auto ms = [](double us) { return Format("%.3f", Ms(us)); };
  const auto quantiles = [&](const LatencyHistogram& h) {
    return "p50 " + ms(h.Percentile(50)) + "  p90 " + ms(h.Percentile(90)) + "  p99 " +
           ms(h.Percentile(99)) + "  max " + ms(static_cast<double>(h.max())) + " ms";
  };
  out << "orbit loadtest: " << report.sessions << " sessions "
      << (report.rate ? "x " + Format("%g", *report.rate) + " frames/s (open loop)"
                      : std::string("(closed loop)"))
      << ", " << report.engine << ", " << (report.image_frames ? "image" : "descriptor")
      << " frames, " << Format("%g", report.duration_seconds) << " s on " << report.server
      << (report.connections > 1 ? " over " + std::to_string(report.connections) + " connections"
                                 : std::string())
      << "\n";
  out << "frames       " << report.frames_sent << " sent, " << report.frames_answered
      << " answered in " << Format("%.2f", report.elapsed_seconds)
      << " s: " << Format("%.1f", report.FramesPerSecond()) << " frames/s\n";
  out << "round trip   " << quantiles(report.round_trip) << "; worst session's p99 "
      << ms(report.worst_session_p99_us) << " ms";
  if (report.sessions_p99_above_5ms > 0) {
    out << " (" << report.sessions_p99_above_5ms << " sessions above 5 ms)";
  }
  out << "\n";
  out << "sessions     " << report.sessions_opened << " opened, " << report.sessions_failed
      << " failed";
  if (report.sessions_cancelled > 0) {
    out << ", " << report.sessions_cancelled << " cancelled with updates still owed";
  }
  out << "\n";
  out << "errors      ";
  if (report.errors.empty()) out << " none";
  for (const auto& [name, count] : report.errors) out << " " << name << " " << count;
  out << "\n";
  out << "server       processing p50 " << Format("%.0f", report.processing.Percentile(50))
      << " us, p99 " << Format("%.0f", report.processing.Percentile(99)) << " us";
  const Json json = LoadReportJson(report);
  const auto cpu_text = [](const Json& cpu) {
    return "CPU " + Format("%.2f", cpu["cpu_seconds"].get<double>()) +
           " s = " + Format("%.1f", cpu["cpu_us_per_frame"].get<double>()) + " us/frame (" +
           Format("%.1f", cpu["cpu_percent"].get<double>()) + "% of a core)";
  };
  if (json["server"].contains("cpu_seconds")) {
    out << "; " << cpu_text(json["server"]) << "; RSS "
        << Format("%.1f", json["server"]["rss_mb_start"].get<double>()) << " -> "
        << Format("%.1f", json["server"]["rss_mb_end"].get<double>()) << " MB";
  }
  if (!report.server_rss_samples.empty()) {
    out << "\nserver RSS  ";
    for (const auto& [seconds, bytes] : report.server_rss_samples) {
      out << " " << Format("%.0f", seconds) << "s " << Format("%.1f", Megabytes(bytes)) << " MB;";
    }
  }
  out << "\n";
  out << "generator    " << cpu_text(json["generator"]) << "\n";
  if (report.enrollments_run) {
    out << "enrollments  " << report.enrollments_done << " of " << report.enrollment_views
        << " views each: " << quantiles(report.enrollment) << "; " << report.enrollments_deleted
        << (report.deleted_during ? " deleted during the load\n" : " deleted afterwards\n");
    out << "  frames meanwhile  " << quantiles(report.round_trip_enrolling) << " ("
        << report.round_trip_enrolling.count() << " frames)\n";
  }
  return out.str();
}

}  // namespace orbit
