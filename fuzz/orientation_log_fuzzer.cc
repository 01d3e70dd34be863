// Fuzz target: a capture's orientation log (client/orientation_log.h, OrientationLog::Parse: the
// CSV `orbit enroll --video` and `orbit recognize --video` read with --orientation,
// docs/capture.md) and a box as --box takes it (client/capture_reader.h, ParseBox: the input's
// first line).
//
// Input: the log's text.
//
// Checked beyond "no crash": only std::invalid_argument is thrown; a log read holds at least one
// reading, its times finite, not negative and increasing (whole numbers for frame_index logs),
// its azimuths finite and its elevations in [-90, 90]; every time from the first reading to the
// last (each reading's and each midpoint) gets an azimuth in [0, 360) and an elevation, when
// there is one, in [-90, 90]; a time before the first or after the last is refused; a box
// parsed has x, y >= 0 and a positive width and height.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "client/capture_reader.h"
#include "client/orientation_log.h"
#include "fuzz/fuzz_check.h"

namespace {

void CheckOrientation(const orbit::FrameOrientation& orientation) {
  ORBIT_FUZZ_CHECK(orientation.azimuth_deg >= 0 && orientation.azimuth_deg < 360);
  ORBIT_FUZZ_CHECK(!orientation.elevation_deg ||
                   (*orientation.elevation_deg >= -90 && *orientation.elevation_deg <= 90));
}

bool Refused(const orbit::OrientationLog& log, double time) {
  try {
    const bool frames = log.clock() == orbit::OrientationClock::kFrameIndex;
    log.At(frames ? static_cast<long>(std::floor(time)) : 0, time);
  } catch (const std::invalid_argument&) {
    return true;
  }
  return false;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace orbit;
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const cv::Rect box = ParseBox(text.substr(0, text.find('\n')));
    ORBIT_FUZZ_CHECK(box.x >= 0 && box.y >= 0 && box.width > 0 && box.height > 0);
  } catch (const std::invalid_argument&) {
  }

  std::istringstream in(text);
  std::optional<OrientationLog> parsed;
  try {
    parsed.emplace(OrientationLog::Parse(in, "fuzz.csv"));
  } catch (const std::invalid_argument&) {
    return 0;
  }
  const OrientationLog& log = *parsed;
  const bool frames = log.clock() == OrientationClock::kFrameIndex;
  const auto& readings = log.readings();
  ORBIT_FUZZ_CHECK(!readings.empty());
  for (std::size_t i = 0; i < readings.size(); ++i) {
    const OrientationReading& r = readings[i];
    ORBIT_FUZZ_CHECK(std::isfinite(r.time) && r.time >= 0 && std::isfinite(r.azimuth_deg));
    ORBIT_FUZZ_CHECK(!frames || r.time == std::floor(r.time));
    ORBIT_FUZZ_CHECK(!r.elevation_deg || (*r.elevation_deg >= -90 && *r.elevation_deg <= 90));
    ORBIT_FUZZ_CHECK(i == 0 || r.time > readings[i - 1].time);
    // Frame logs are read at whole frames only; timestamp logs at any time.
    CheckOrientation(log.At(frames ? static_cast<long>(r.time) : 0, r.time));
    if (i > 0 && !frames) {
      const double middle = readings[i - 1].time + (r.time - readings[i - 1].time) / 2;
      CheckOrientation(log.At(0, middle));
    }
  }
  ORBIT_FUZZ_CHECK(Refused(log, readings.front().time - 1));
  ORBIT_FUZZ_CHECK(Refused(log, readings.back().time + 1));
  return 0;
}
