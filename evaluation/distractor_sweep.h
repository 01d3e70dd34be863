// A sweep of the number of distractors (`orbit eval --distractors 0,1000,9900`): the same
// evaluation among more and more other objects, so a report shows how hit rate and the
// rejection of unknown objects hold as the catalogue grows (docs/design.md#distractors).
//
// Every function takes the reports of one sweep: one per distractor count, in the sweep's
// order, each from the same options but the count, so with the same cells in the same order.
// Pure and thread-safe.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "evaluation/evaluation_runner.h"

namespace orbit {

// The sweep as Markdown: per variant, one row per distortion, method and n, and per count a
// column of hit rates (%); with unknown objects, then a column per count of unknowns rejected
// (%). Throws std::invalid_argument when the reports are empty or their cells differ.
std::string DistractorSweepMarkdown(const std::vector<EvaluationReport>& reports);

// The sweep as CSV, header
//   distractors,method,variant,distortion,n,trials,hits,hit_rate,unknown_trials,rejected,reject_rate
// Throws as DistractorSweepMarkdown.
void WriteDistractorSweepCsv(const std::vector<EvaluationReport>& reports, std::ostream& out);

// The sweep's figure: one panel per variant (rows) and distortion (columns), against the
// distractor count (evenly spaced ticks, whatever the counts), a line per method and n for the
// hit rate and, with unknown objects, one for the unknowns rejected. Throws as
// DistractorSweepMarkdown and DrawLineFigure.
cv::Mat DrawDistractorSweepPlot(const std::vector<EvaluationReport>& reports);

}  // namespace orbit
