#include "cli/progress_bar.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace orbit {
namespace {

constexpr int kBarWidth = 30;
constexpr std::chrono::milliseconds kRedrawInterval(200);

std::string Duration(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char buffer[32];
  if (s >= 3600) {
    std::snprintf(buffer, sizeof buffer, "%ldh%02ldm", s / 3600, s / 60 % 60);
  } else if (s >= 60) {
    std::snprintf(buffer, sizeof buffer, "%ldm%02lds", s / 60, s % 60);
  } else {
    std::snprintf(buffer, sizeof buffer, "%lds", s);
  }
  return buffer;
}

}  // namespace

ProgressBar::ProgressBar(std::ostream& out, bool terminal, std::chrono::milliseconds delay)
    : out_(out), terminal_(terminal), start_(Clock::now()), delay_(delay) {}

ProgressBar::~ProgressBar() {
  if (line_open_) out_ << "\n" << std::flush;
}

std::string ProgressBar::Render(std::string_view stage, std::size_t done, std::size_t total,
                                double seconds_left) {
  const double fraction = total > 0 ? std::min(1.0, double(done) / double(total)) : 1.0;
  const int filled = static_cast<int>(fraction * kBarWidth);
  std::string bar(kBarWidth, ' ');
  std::fill_n(bar.begin(), filled, '=');
  if (filled < kBarWidth && done > 0) bar[filled] = '>';
  char percent[8];
  std::snprintf(percent, sizeof percent, "%3d%%", static_cast<int>(fraction * 100));
  std::string line = std::string(stage) + " [" + bar + "] " + percent + " " + std::to_string(done) +
                     "/" + std::to_string(total);
  if (done < total && seconds_left >= 0) line += ", " + Duration(seconds_left) + " left";
  return line;
}

void ProgressBar::Update(std::string_view stage, std::size_t done, std::size_t total) {
  const Clock::time_point now = Clock::now();
  if (stage != stage_) {
    if (line_open_) out_ << "\n";
    line_open_ = false;
    stage_ = stage;
    stage_start_ = now;
    last_tenth_ = -1;
    last_draw_ = Clock::time_point();
  }
  if (now - start_ < delay_) return;
  const double elapsed = std::chrono::duration<double>(now - stage_start_).count();
  const double left =
      done > 0 ? elapsed * double(total - std::min(done, total)) / double(done) : -1;
  if (terminal_) {
    if (done < total && now - last_draw_ < kRedrawInterval) return;
    last_draw_ = now;
    out_ << "\r" << Render(stage, done, total, left) << "\x1b[K" << std::flush;
    line_open_ = done < total;
    if (!line_open_) out_ << "\n" << std::flush;
  } else {
    const int tenth = total > 0 ? static_cast<int>(10 * done / total) : 10;
    if (tenth == last_tenth_) return;
    last_tenth_ = tenth;
    out_ << Render(stage, done, total, left) << "\n" << std::flush;
  }
}

}  // namespace orbit
