// The picture of an evaluation (`orbit eval --plot`): hit rate against the query length n, like
// the thesis' figures. One panel per descriptor variant (rows) and distortion (columns), one
// line per method with its own colour and marker, a shared legend, axis labels on every panel.
// Drawn with OpenCV's imgproc drawing functions only.
//
// All functions are thread-safe (they only read the report).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

#include "evaluation/evaluation_runner.h"

namespace orbit {

// A figure of hit-rate panels, the drawing both plots share: panels laid out `columns` to a row,
// each with its x ticks and lines (y: hit rate in [0, 1], drawn in percent), one colour and
// marker per line name across all panels, and one legend.
struct LineSeries {
  std::string name;
  std::vector<std::pair<double, double>> points;  // (x, hit rate in [0, 1]), in drawing order
};
struct LinePanel {
  std::string title;
  std::string x_label;
  std::string y_label = "hit rate (%)";
  std::vector<std::pair<double, std::string>> ticks;  // (x, label), ascending x: the axis' span
  std::vector<LineSeries> series;
};
struct LineFigure {
  std::string title;
  int columns = 1;
  std::vector<LinePanel> panels;
};

// The figure as a CV_8UC3 image on a white background. Throws std::invalid_argument when it
// has no panels.
cv::Mat DrawLineFigure(const LineFigure& figure);

// Writes `image` to `path` as PNG. Throws std::runtime_error naming the path when it cannot.
void WritePng(const cv::Mat& image, const std::string& path);

// The figure of `report`: hit rate against n. Throws std::invalid_argument when the report has
// no cells.
cv::Mat DrawHitRatePlot(const EvaluationReport& report);

// Draws the figure and writes it to `path` as PNG. Throws std::runtime_error naming the path
// when it cannot be written, and as DrawHitRatePlot.
void WriteHitRatePlot(const EvaluationReport& report, const std::string& path);

}  // namespace orbit
