// OrientationLog: the device's orientation readings during a capture (docs/capture.md), and the
// azimuth (and elevation) they give each video frame.
//
// A log is a CSV file, one reading per line, at any rate:
//   timestamp_ms,azimuth_deg[,elevation_deg]     times in ms from the video's first frame
// or, for a device that stamped every frame itself, one line per frame:
//   frame_index,azimuth_deg[,elevation_deg]      frame 0 is the video's first frame
// The header line names which (a file without one is read as timestamps); '#' lines and blank
// lines are ignored. Azimuths are any finite degrees (only differences matter, as everywhere in
// Orbit); elevations are in [-90, 90].
//
// Alignment: a frame between two readings gets the azimuth on the shorter arc between them,
// interpolated linearly in time (350 then 10 degrees gives 0 halfway, not 180), and the
// elevation interpolated linearly; a frame on a reading gets that reading. A frame before the
// first reading or after the last is not covered: nothing is extrapolated.
//
// Errors: every refusal is std::invalid_argument whose message names the file and line and
// says what is allowed: a time or frame that does not increase or lies outside
// [0, kMaxOrientationTime], a non-finite or unparsable
// value, an elevation outside [-90, 90], a log without readings, a frame the log does not cover.
// Thread safety: immutable once built; any number of threads may read it.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace orbit {

// The largest time a log may give, in its clock's unit (1e12 ms is 31 years; frame indices fit
// a long and stay exact in a double).
inline constexpr double kMaxOrientationTime = 1e12;

// What a log's first column counts.
enum class OrientationClock {
  kTimestampMs,  // milliseconds from the first frame; readings at any rate
  kFrameIndex,   // the frame's index in the video; one reading per frame
};

struct OrientationReading {
  double time = 0;  // ms or frame index, as the log's clock
  double azimuth_deg = 0;
  std::optional<double> elevation_deg;
  int line = 0;  // line in the file, for messages (0 when built in memory)
};

// Where the camera pointed for one frame.
struct FrameOrientation {
  double azimuth_deg = 0;  // in [0, 360)
  std::optional<double> elevation_deg;
};

class OrientationLog {
 public:
  // Validates `readings` (in file order) as a log named `source` in messages.
  // Throws std::invalid_argument as the header comment says.
  OrientationLog(std::vector<OrientationReading> readings, OrientationClock clock,
                 std::string source = "orientation log");

  // Parses CSV text as described above; `source` names it in messages (the file's path).
  static OrientationLog Parse(std::istream& text, const std::string& source);
  // Parse of the file at `path`; std::runtime_error naming it when it cannot be opened.
  static OrientationLog ReadFile(const std::string& path);

  // The orientation of the frame with index `frame_index` shown at `timestamp_ms` (from the
  // first frame). Throws std::invalid_argument naming the source, the frame and the covered
  // span when the log does not cover it.
  FrameOrientation At(long frame_index, double timestamp_ms) const;

  // Throws as At() when frames 0 .. frame_count - 1 at 0 .. last_timestamp_ms are not all
  // covered: the check made once a video's length is known, before anything is sent.
  void RequireCovers(long frame_count, double last_timestamp_ms) const;

  OrientationClock clock() const { return clock_; }
  const std::vector<OrientationReading>& readings() const { return readings_; }
  const std::string& source() const { return source_; }

 private:
  // The span covered in the log's clock: [front().time, back().time].
  std::string CoveredSpan() const;

  std::vector<OrientationReading> readings_;
  OrientationClock clock_;
  std::string source_;
};

}  // namespace orbit
