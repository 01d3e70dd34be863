#include "client/orientation_log.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/base/angles.h"

namespace orbit {
namespace {

constexpr double kMaxElevation = 90;  // elevations are in [-kMaxElevation, kMaxElevation]

std::string ClockName(OrientationClock clock) {
  return clock == OrientationClock::kTimestampMs ? "timestamp_ms" : "frame_index";
}

std::string Where(const std::string& source, int line) {
  return line > 0 ? source + ":" + std::to_string(line) : source;
}

std::string Number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

std::string Trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

std::vector<std::string> SplitFields(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  std::string field;
  while (std::getline(in, field, ',')) fields.push_back(Trim(field));
  if (!line.empty() && line.back() == ',') fields.push_back("");
  return fields;
}

// A whole field as a double; nullopt when it is not one number. Non-finite spellings ("nan",
// "inf") parse, so that they are refused as non-finite rather than as unreadable.
std::optional<double> ParseNumber(const std::string& field) {
  if (field.empty()) return std::nullopt;
  char* end = nullptr;
  const double value = std::strtod(field.c_str(), &end);
  if (end != field.c_str() + field.size()) return std::nullopt;
  return value;
}

}  // namespace

OrientationLog::OrientationLog(std::vector<OrientationReading> readings, OrientationClock clock,
                               std::string source)
    : readings_(std::move(readings)), clock_(clock), source_(std::move(source)) {
  if (readings_.empty()) {
    throw std::invalid_argument(source_ + ": no orientation readings (lines " + ClockName(clock_) +
                                ",azimuth_deg[,elevation_deg])");
  }
  for (std::size_t i = 0; i < readings_.size(); ++i) {
    const OrientationReading& r = readings_[i];
    const std::string where = Where(source_, r.line);
    if (!std::isfinite(r.time) || !std::isfinite(r.azimuth_deg) ||
        (r.elevation_deg && !std::isfinite(*r.elevation_deg))) {
      throw std::invalid_argument(where + ": values must be finite numbers");
    }
    if (r.time < 0 || r.time > kMaxOrientationTime) {
      throw std::invalid_argument(where + ": " + ClockName(clock_) + " " + Number(r.time) +
                                  " is outside [0, 1e12]; it counts from the video's first "
                                  "frame (0)");
    }
    if (clock_ == OrientationClock::kFrameIndex && r.time != std::floor(r.time)) {
      throw std::invalid_argument(where + ": frame_index " + Number(r.time) +
                                  " is not a whole number");
    }
    if (r.elevation_deg && std::abs(*r.elevation_deg) > kMaxElevation) {
      throw std::invalid_argument(where + ": elevation_deg " + Number(*r.elevation_deg) +
                                  " is outside [-90, 90]");
    }
    if (i > 0 && !(r.time > readings_[i - 1].time)) {
      throw std::invalid_argument(where + ": " + ClockName(clock_) + " " + Number(r.time) +
                                  " goes backwards in time: it must be greater than the "
                                  "previous reading's " +
                                  Number(readings_[i - 1].time));
    }
  }
}

OrientationLog OrientationLog::Parse(std::istream& text, const std::string& source) {
  std::vector<OrientationReading> readings;
  OrientationClock clock = OrientationClock::kTimestampMs;
  std::string line;
  int number = 0;
  bool first_content = true;
  while (std::getline(text, line)) {
    ++number;
    const std::string trimmed = Trim(line);
    if (trimmed.empty() || trimmed[0] == '#') continue;
    const std::vector<std::string> fields = SplitFields(trimmed);
    if (first_content) {
      first_content = false;
      if (!ParseNumber(fields[0])) {  // a header
        if (fields[0] == "frame_index") {
          clock = OrientationClock::kFrameIndex;
        } else if (fields[0] != "timestamp_ms") {
          throw std::invalid_argument(Where(source, number) + ": unknown header '" + trimmed +
                                      "': expected timestamp_ms,azimuth_deg[,elevation_deg] "
                                      "or frame_index,azimuth_deg[,elevation_deg]");
        }
        if (fields.size() < 2 || fields.size() > 3 || fields[1] != "azimuth_deg" ||
            (fields.size() == 3 && fields[2] != "elevation_deg")) {
          throw std::invalid_argument(Where(source, number) + ": header '" + trimmed +
                                      "' must be " + ClockName(clock) +
                                      ",azimuth_deg[,elevation_deg]");
        }
        continue;
      }
    }
    if (fields.size() < 2 || fields.size() > 3) {
      throw std::invalid_argument(Where(source, number) + ": expected 2 or 3 values (" +
                                  ClockName(clock) + ",azimuth_deg[,elevation_deg]), got " +
                                  std::to_string(fields.size()));
    }
    OrientationReading reading;
    reading.line = number;
    std::optional<double> values[3];
    for (std::size_t f = 0; f < fields.size(); ++f) {
      values[f] = ParseNumber(fields[f]);
      if (!values[f]) {
        throw std::invalid_argument(Where(source, number) + ": '" + fields[f] +
                                    "' is not a number");
      }
    }
    reading.time = *values[0];
    reading.azimuth_deg = *values[1];
    reading.elevation_deg = values[2];
    readings.push_back(reading);
  }
  return OrientationLog(std::move(readings), clock, source);
}

OrientationLog OrientationLog::ReadFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read orientation log " + path);
  return Parse(in, path);
}

std::string OrientationLog::CoveredSpan() const {
  return ClockName(clock_) + " " + Number(readings_.front().time) + " to " +
         Number(readings_.back().time);
}

FrameOrientation OrientationLog::At(long frame_index, double timestamp_ms) const {
  const double t =
      clock_ == OrientationClock::kTimestampMs ? timestamp_ms : static_cast<double>(frame_index);
  if (!(t >= readings_.front().time && t <= readings_.back().time)) {
    throw std::invalid_argument(
        source_ + " does not cover frame " + std::to_string(frame_index) + " (at " +
        Number(timestamp_ms) + " ms): it covers " + CoveredSpan() +
        "; a log must span the whole video, from its first frame to its last");
  }
  // The first reading at or after t.
  const auto after =
      std::lower_bound(readings_.begin(), readings_.end(), t,
                       [](const OrientationReading& r, double time) { return r.time < time; });
  if (after->time == t) {
    return {NormaliseAzimuth(after->azimuth_deg), after->elevation_deg};
  }
  const OrientationReading& before = *(after - 1);
  const double fraction = (t - before.time) / (after->time - before.time);
  FrameOrientation orientation;
  orientation.azimuth_deg = NormaliseAzimuth(
      before.azimuth_deg + fraction * AzimuthChange(before.azimuth_deg, after->azimuth_deg));
  if (before.elevation_deg && after->elevation_deg) {
    orientation.elevation_deg =
        *before.elevation_deg + fraction * (*after->elevation_deg - *before.elevation_deg);
  }
  return orientation;
}

void OrientationLog::RequireCovers(long frame_count, double last_timestamp_ms) const {
  if (frame_count <= 0) return;
  At(0, 0);
  At(frame_count - 1, last_timestamp_ms);
}

}  // namespace orbit
