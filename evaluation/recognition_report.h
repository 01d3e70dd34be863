// The recognition reports of `orbit eval`: what the accept / unknown decision, the
// confidence and the pose estimate did, per method x variant x distortion x n, from the
// per-query verdicts the runner keeps (EvaluationCell::verdicts).
//
//   known queries:   right and accepted / rejected / accepted but wrong (top-1 wrong)
//   unknown queries: rejected / accepted
//   pose: median and 90th percentile of the error of known hits, degrees (the protocol's
//         queries only: a captured query's azimuths do not say which side of the model it shows)
//   reliability: confidence in bins of 0.1 against the share of those updates that were right
//                (a right update: a known query whose top-1 object is right), and the bin of
//                at least kReliabilityGapLeast updates where the two lie farthest apart
//   separation: what any threshold on the unknown statistic could do, in hindsight
//
// Pure functions of the report; thread-safe.
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "evaluation/evaluation_plot.h"
#include "evaluation/evaluation_runner.h"

namespace orbit {

// The recognition table (one row per cell with queries) and the pose errors, as Markdown.
std::string RecognitionMarkdown(const EvaluationReport& report);

// One row per bin of confidence [b/10, (b+1)/10) over the updates of `cells`.
struct ReliabilityBin {
  double low = 0, high = 0;
  int updates = 0;
  int right = 0;
  double mean_confidence = 0;
};
std::vector<ReliabilityBin> Reliability(const std::vector<const EvaluationCell*>& cells);

// The bins the confidence is judged on: at least this many updates (fewer say too little).
inline constexpr int kReliabilityGapLeast = 100;

// The bin of at least `least` updates whose share right lies farthest from its mean
// confidence, and that gap in points: 100 x (right / updates - mean confidence), positive where
// the confidence says less than it is worth. Of equal gaps the lower bin; none when no bin holds
// `least` updates.
struct ReliabilityGap {
  ReliabilityBin bin;
  double points = 0;
};
std::optional<ReliabilityGap> LargestReliabilityGap(const std::vector<ReliabilityBin>& bins,
                                                    int least);

// The reliability table of every method's cells pooled over distortions and n, as Markdown.
std::string ReliabilityMarkdown(const EvaluationReport& report);

// What a threshold on the unknown statistic U could do on one cell in hindsight, the cell's own
// queries choosing it: whether a cell's known / unknown pair falls short because the rule's
// threshold is off or because no threshold on U reaches it.
//   area: the chance that a known query answered right has a lower U than an unknown query
//         (ties count half): 1 where U separates them, 0.5 where it says nothing;
//   known_right[i]: the share of the cell's known queries answered right whose U lies below
//         the most lenient threshold that still rejects kSeparationRejected[i] of its unknown
//         queries (of N unknown queries at most floor((1 - r) N) accepted; below every
//         unknown U when that is 0).
inline constexpr double kSeparationRejected[] = {0.95, 0.9, 0.8, 0.75};
struct UnknownSeparation {
  double area = 0;
  std::vector<double> known_right;  // [i]: at kSeparationRejected[i]
};
// None when the cell lacks known or unknown queries, or a verdict's U is not stated (NaN: a
// server's answers).
std::optional<UnknownSeparation> SeparationOf(const EvaluationCell& cell);

// One row per cell with a separation, as Markdown ("" when none has one).
std::string SeparationMarkdown(const EvaluationReport& report);

// The threshold sweep (`orbit eval --recognition-plot`): for targets t from 0.01 to 1, the
// share of known queries right and accepted (accepted: p-value <= t) against the share of
// unknown queries accepted, one panel per variant x distortion, one line per method x n. The
// curves are the null's rule alone: the known share (docs/design.md#known-share) and the known
// ceiling (docs/design.md#known-ceiling) do not move with t and are left out, so the decisions
// in the tables lie on the curve at t = false_accept_rate only where neither moves the
// threshold (the share raises it among look-alikes, the ceiling holds it on few objects).
// Throws std::invalid_argument when no
// cell has both known and unknown queries.
LineFigure RecognitionCurves(const EvaluationReport& report);

// Every query's verdict as CSV: method,variant,distortion,n,known,hit,decision,
// unknown_statistic,unknown_p_value,confidence,pose_error,pose_spread,noise_sigma,blur (empty
// pose fields when not measured; unknown_statistic and unknown_p_value empty when the answer
// did not state them, as a server's; noise_sigma and blur, the window's mean readings, empty
// without them).
// Throws std::runtime_error when the stream fails.
void WriteVerdictsCsv(const EvaluationReport& report, std::ostream& out);

}  // namespace orbit
