#include "evaluation/evaluation_plot.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string_view>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "evaluation/evaluation_report.h"

namespace orbit {
namespace {

constexpr int kPanelWidth = 460;
constexpr int kPanelHeight = 340;
constexpr int kMarginLeft = 62;  // room for the y tick labels and the axis label
constexpr int kMarginRight = 18;
constexpr int kMarginTop = 34;     // the panel's title
constexpr int kMarginBottom = 52;  // x tick labels and the axis label
constexpr int kTitleHeight = 40;
constexpr int kLegendEntryWidth = 130;
constexpr int kLegendRowHeight = 26;

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
const cv::Scalar kBlack(0, 0, 0);
const cv::Scalar kGrid(225, 225, 225);
const cv::Scalar kWhite(255, 255, 255);

// Tableau-like palette (BGR), one colour per method; cycles after ten methods.
const std::array<cv::Scalar, 10> kPalette = {cv::Scalar(180, 119, 31),  cv::Scalar(14, 127, 255),
                                             cv::Scalar(44, 160, 44),   cv::Scalar(40, 39, 214),
                                             cv::Scalar(189, 103, 148), cv::Scalar(75, 86, 140),
                                             cv::Scalar(194, 119, 227), cv::Scalar(127, 127, 127),
                                             cv::Scalar(34, 189, 188),  cv::Scalar(207, 190, 23)};

// Draws marker `shape` (cycled) centred at `p`, so lines stay apart when colours are hard to tell.
void DrawMarker(cv::Mat& image, cv::Point p, int shape, const cv::Scalar& colour) {
  constexpr int r = 5;
  switch (shape % 5) {
    case 0: cv::circle(image, p, r, colour, cv::FILLED, cv::LINE_AA); break;
    case 1:
      cv::rectangle(image, p - cv::Point(r - 1, r - 1), p + cv::Point(r - 1, r - 1), colour,
                    cv::FILLED, cv::LINE_AA);
      break;
    case 2: {
      const std::vector<cv::Point> triangle{p + cv::Point(0, -r - 1), p + cv::Point(r, r - 1),
                                            p + cv::Point(-r, r - 1)};
      cv::fillConvexPoly(image, triangle, colour, cv::LINE_AA);
      break;
    }
    case 3: {
      const std::vector<cv::Point> diamond{p + cv::Point(0, -r - 1), p + cv::Point(r + 1, 0),
                                           p + cv::Point(0, r + 1), p + cv::Point(-r - 1, 0)};
      cv::fillConvexPoly(image, diamond, colour, cv::LINE_AA);
      break;
    }
    default: cv::drawMarker(image, p, colour, cv::MARKER_CROSS, 2 * r + 3, 2, cv::LINE_AA);
  }
}

void PutText(cv::Mat& image, const std::string& text, cv::Point origin, double scale,
             int thickness = 1) {
  cv::putText(image, text, origin, kFont, scale, kBlack, thickness, cv::LINE_AA);
}

// Text centred horizontally on x, baseline at y.
void PutCentred(cv::Mat& image, const std::string& text, int x, int y, double scale,
                int thickness = 1) {
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, kFont, scale, thickness, &baseline);
  PutText(image, text, {x - size.width / 2, y}, scale, thickness);
}

// Text rotated a quarter turn counter-clockwise (read bottom to top), centred at `centre`.
void PutVertical(cv::Mat& image, const std::string& text, cv::Point centre, double scale) {
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, kFont, scale, 1, &baseline);
  cv::Mat strip(size.height + baseline + 4, size.width + 4, CV_8UC3, kWhite);
  PutText(strip, text, {2, size.height + 2}, scale);
  cv::Mat rotated;
  cv::rotate(strip, rotated, cv::ROTATE_90_COUNTERCLOCKWISE);
  const cv::Rect where(centre.x - rotated.cols / 2, centre.y - rotated.rows / 2, rotated.cols,
                       rotated.rows);
  const cv::Rect inside = where & cv::Rect(0, 0, image.cols, image.rows);
  if (inside.area() == 0) return;
  rotated(cv::Rect(inside.x - where.x, inside.y - where.y, inside.width, inside.height))
      .copyTo(image(inside));
}

template <typename T>
void AddOnce(std::vector<T>& values, const T& value) {
  if (std::find(values.begin(), values.end(), value) == values.end()) values.push_back(value);
}

}  // namespace

cv::Mat DrawLineFigure(const LineFigure& figure) {
  if (figure.panels.empty() || figure.columns < 1) {
    throw std::invalid_argument("DrawLineFigure: the figure has no panels");
  }
  std::vector<std::string> series;  // legend entries, in order of first appearance
  for (const LinePanel& panel : figure.panels) {
    for (const LineSeries& line : panel.series) AddOnce(series, line.name);
  }
  const int columns = std::min<int>(figure.columns, static_cast<int>(figure.panels.size()));
  const int rows = (static_cast<int>(figure.panels.size()) + columns - 1) / columns;
  int entry_width = kLegendEntryWidth;  // wide enough for the longest name
  for (const std::string& name : series) {
    int baseline = 0;
    entry_width = std::max(entry_width, cv::getTextSize(name, kFont, 0.5, 1, &baseline).width + 60);
  }
  const int width = std::max(columns * kPanelWidth, 2 * entry_width);
  const int legend_per_row = std::max(1, width / entry_width);
  const int legend_rows = (static_cast<int>(series.size()) + legend_per_row - 1) / legend_per_row;
  const int height = kTitleHeight + rows * kPanelHeight + legend_rows * kLegendRowHeight + 12;
  cv::Mat image(height, width, CV_8UC3, kWhite);
  PutCentred(image, figure.title, width / 2, 26, 0.6, 1);

  const int plot_width = kPanelWidth - kMarginLeft - kMarginRight;
  const int plot_height = kPanelHeight - kMarginTop - kMarginBottom;
  const auto y_of = [&](double rate, int top) {
    return top + static_cast<int>(std::lround((1.0 - rate) * plot_height));
  };
  for (std::size_t p = 0; p < figure.panels.size(); ++p) {
    const LinePanel& panel = figure.panels[p];
    const double x_min = panel.ticks.empty() ? 0 : panel.ticks.front().first;
    const double x_max = panel.ticks.empty() ? 1 : panel.ticks.back().first;
    const int panel_x = static_cast<int>(p) % columns * kPanelWidth;
    const int panel_y = kTitleHeight + static_cast<int>(p) / columns * kPanelHeight;
    const int left = panel_x + kMarginLeft, top = panel_y + kMarginTop;
    const int right = left + plot_width, bottom = top + plot_height;
    const auto x_of = [&](double x) {
      if (x_max == x_min) return left + plot_width / 2;
      const double t = (x - x_min) / (x_max - x_min);
      return left + static_cast<int>(std::lround(12 + t * (plot_width - 24)));
    };

    PutCentred(image, panel.title, (left + right) / 2, panel_y + 22, 0.55, 1);
    for (int percent = 0; percent <= 100; percent += 20) {
      const int y = y_of(percent / 100.0, top);
      cv::line(image, {left, y}, {right, y}, kGrid, 1);
      const std::string label = std::to_string(percent);
      int baseline = 0;
      const cv::Size size = cv::getTextSize(label, kFont, 0.4, 1, &baseline);
      PutText(image, label, {left - 6 - size.width, y + size.height / 2}, 0.4);
    }
    for (const auto& [x, label] : panel.ticks) {
      cv::line(image, {x_of(x), bottom}, {x_of(x), bottom + 4}, kBlack, 1);
      PutCentred(image, label, x_of(x), bottom + 18, 0.4);
    }
    cv::rectangle(image, {left, top}, {right, bottom}, kBlack, 1);
    PutCentred(image, panel.x_label, (left + right) / 2, bottom + 40, 0.45);
    PutVertical(image, panel.y_label, {panel_x + 16, (top + bottom) / 2}, 0.45);

    for (const LineSeries& line : panel.series) {
      const int m =
          static_cast<int>(std::find(series.begin(), series.end(), line.name) - series.begin());
      std::vector<cv::Point> points;
      for (const auto& [x, rate] : line.points) points.push_back({x_of(x), y_of(rate, top)});
      const cv::Scalar& colour = kPalette[m % kPalette.size()];
      cv::polylines(image, points, false, colour, 2, cv::LINE_AA);
      for (const cv::Point& point : points) DrawMarker(image, point, m, colour);
    }
  }

  const int legend_top = kTitleHeight + rows * kPanelHeight + 4;
  const int legend_left =
      (width - std::min<int>(legend_per_row, static_cast<int>(series.size())) * entry_width) / 2;
  for (std::size_t m = 0; m < series.size(); ++m) {
    const int row = static_cast<int>(m) / legend_per_row,
              col = static_cast<int>(m) % legend_per_row;
    const int x = legend_left + col * entry_width;
    const int y = legend_top + row * kLegendRowHeight + kLegendRowHeight / 2;
    const cv::Scalar& colour = kPalette[m % kPalette.size()];
    cv::line(image, {x, y}, {x + 36, y}, colour, 2, cv::LINE_AA);
    DrawMarker(image, {x + 18, y}, static_cast<int>(m), colour);
    PutText(image, series[m], {x + 44, y + 5}, 0.5);
  }
  return image;
}

void WritePng(const cv::Mat& image, const std::string& path) {
  bool written = false;
  try {
    written = cv::imwrite(path, image, {cv::IMWRITE_PNG_COMPRESSION, 6});
  } catch (const cv::Exception& e) {
    throw std::runtime_error(path + ": cannot write the plot: " + e.what());
  }
  if (!written) throw std::runtime_error(path + ": cannot write the plot");
}

cv::Mat DrawHitRatePlot(const EvaluationReport& report) {
  if (report.cells.empty()) throw std::invalid_argument("DrawHitRatePlot: the report is empty");
  std::vector<DescriptorVariant> variants;
  std::vector<std::string> distortions;
  std::vector<int> ns;
  for (const EvaluationCell& cell : report.cells) {
    AddOnce(variants, cell.variant);
    AddOnce(distortions, cell.distortion);
    AddOnce(ns, cell.n);
  }
  std::sort(ns.begin(), ns.end());

  LineFigure figure;
  figure.title = "Top-1 hit rate vs query length n (" +
                 std::to_string(report.cells.front().trials) + " queries per point, seed " +
                 std::to_string(report.seed) + ", index " +
                 (report.search == SearchMode::kExact ? "exact" : "kdtree") + ")";
  figure.columns = static_cast<int>(distortions.size());
  for (const DescriptorVariant variant : variants) {
    for (const std::string& distortion : distortions) {
      LinePanel& panel = figure.panels.emplace_back();
      panel.title = std::string(VariantName(variant)) + " / " + DistortionLabel(distortion);
      panel.x_label = "n (query frames)";
      for (int n : ns) panel.ticks.emplace_back(n, std::to_string(n));
      for (const EvaluationCell& cell : report.cells) {
        if (cell.variant != variant || cell.distortion != distortion) continue;
        auto line = std::find_if(panel.series.begin(), panel.series.end(),
                                 [&](const LineSeries& s) { return s.name == cell.method; });
        if (line == panel.series.end())
          line = panel.series.insert(panel.series.end(), {cell.method, {}});
        line->points.emplace_back(cell.n, cell.hit_rate());
      }
    }
  }
  return DrawLineFigure(figure);
}

void WriteHitRatePlot(const EvaluationReport& report, const std::string& path) {
  WritePng(DrawHitRatePlot(report), path);
}

}  // namespace orbit
