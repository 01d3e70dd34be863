// The picture of an evaluation (`orbit eval --plot`): hit rate against the query length n, like
// the thesis' figures. One panel per descriptor variant (rows) and distortion (columns), one
// line per method with its own colour and marker, a shared legend, axis labels on every panel.
// Drawn with OpenCV's imgproc drawing functions only.
//
// All functions are thread-safe (they only read the report).
#pragma once

#include <string>

#include <opencv2/core.hpp>

#include "evaluation/evaluation_runner.h"

namespace orbit {

// The figure as a CV_8UC3 image on a white background. Throws std::invalid_argument when the
// report has no cells.
cv::Mat DrawHitRatePlot(const EvaluationReport& report);

// Draws the figure and writes it to `path` as PNG. Throws std::runtime_error naming the path
// when it cannot be written, and as DrawHitRatePlot.
void WriteHitRatePlot(const EvaluationReport& report, const std::string& path);

}  // namespace orbit
