// A sweep of one distortion's strength (`orbit eval --sweep`): the same kind of distortion at
// evenly spaced strengths, so a report shows hit rate against strength rather than at one
// setting that could have been tuned for.
//
// Axes and their default ranges (those of docs/results/robustness.md's sweeps, ends included):
//   mb    blur length 5..25 px; the angle changes from step to step (0, 37, 74, ... degrees
//         modulo 180), so no angle is favoured
//   gn    noise variance 0.002..0.03
//   jpeg  JPEG quality 10..60 (rounded to whole numbers)
//   gain  brightness gain 0.6..1.4
// Text form: AXIS or AXIS:FROM..TO, e.g. "gn", "gn:0.001..0.05", "jpeg:5..95".
//
// Pure and thread-safe.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "evaluation/distortion_spec.h"
#include "evaluation/evaluation_runner.h"

namespace orbit {

inline constexpr int kMinSweepSteps = 2;
inline constexpr int kMaxSweepSteps = 20;

struct DistortionSweep {
  std::string axis;                         // "mb", "gn", "jpeg" or "gain"
  std::string strength;                     // what is swept, e.g. "noise variance"
  std::vector<double> strengths;            // ascending, one per step
  std::vector<DistortionSpec> distortions;  // the distortion at each strength
};

// The sweep `text` describes, with `steps` strengths. Throws std::invalid_argument naming the
// offending text for an unknown axis, a malformed or reversed range, a range outside what the
// distortion accepts (distortion_spec.h), or steps outside kMinSweepSteps..kMaxSweepSteps.
DistortionSweep ParseSweep(std::string_view text, int steps);

// The sweeps' results as Markdown: per sweep, a table with one row per method (and variant)
// and n, one column per strength, hit rates in percent.
std::string SweepMarkdown(const EvaluationReport& report,
                          const std::vector<DistortionSweep>& sweeps);

// The sweeps' results as CSV, header
//   axis,strength,distortion,method,variant,n,trials,hits,hit_rate
void WriteSweepCsv(const EvaluationReport& report, const std::vector<DistortionSweep>& sweeps,
                   std::ostream& out);

// The sweeps' figure: one panel per sweep (columns) and n (rows), hit rate against strength,
// one line per method (and variant). Throws as DrawLineFigure.
cv::Mat DrawSweepPlot(const EvaluationReport& report, const std::vector<DistortionSweep>& sweeps);

}  // namespace orbit
