// ProgressBar: a one-line progress display on a stream (stderr for `orbit eval`), for long runs.
//
// Quiet for short runs: nothing is drawn until `delay` has passed since construction, so a job
// of a few seconds prints nothing. On a terminal the line is redrawn in place ("\r") at most
// every 0.2 s; on a pipe or file a plain line is written when a stage starts and at each tenth
// of it, so logs stay readable. Each stage (e.g. "descriptors", then "trials") gets its own bar.
//
// Thread safety: none; callers serialise Update() (EvaluationOptions::progress is never called
// concurrently).
#pragma once

#include <chrono>
#include <cstddef>
#include <ostream>
#include <string>
#include <string_view>

namespace orbit {

class ProgressBar {
 public:
  // `terminal`: whether `out` is a terminal (redraw in place) or not (one line per tenth).
  ProgressBar(std::ostream& out, bool terminal,
              std::chrono::milliseconds delay = std::chrono::milliseconds(2000));
  ~ProgressBar();  // ends a drawn line with "\n"

  // `done` of `total` tasks of `stage` are complete.
  void Update(std::string_view stage, std::size_t done, std::size_t total);

  // The bar as drawn: "stage [=====>    ]  42% 420/1000, 1m05s left" (width 30).
  static std::string Render(std::string_view stage, std::size_t done, std::size_t total,
                            double seconds_left);

 private:
  using Clock = std::chrono::steady_clock;
  std::ostream& out_;
  const bool terminal_;
  const Clock::time_point start_;
  const std::chrono::milliseconds delay_;
  std::string stage_;
  Clock::time_point stage_start_;
  Clock::time_point last_draw_;
  int last_tenth_ = -1;
  bool line_open_ = false;  // a "\r" line is on screen without its newline
};

}  // namespace orbit
