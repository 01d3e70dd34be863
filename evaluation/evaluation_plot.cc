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
constexpr int kMarginLeft = 62;    // room for the y tick labels and the axis label
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
const std::array<cv::Scalar, 10> kPalette = {
    cv::Scalar(180, 119, 31),  cv::Scalar(14, 127, 255),  cv::Scalar(44, 160, 44),
    cv::Scalar(40, 39, 214),   cv::Scalar(189, 103, 148), cv::Scalar(75, 86, 140),
    cv::Scalar(194, 119, 227), cv::Scalar(127, 127, 127), cv::Scalar(34, 189, 188),
    cv::Scalar(207, 190, 23)};

// Draws marker `shape` (cycled) centred at `p`, so lines stay apart when colours are hard to tell.
void DrawMarker(cv::Mat& image, cv::Point p, int shape, const cv::Scalar& colour) {
  constexpr int r = 5;
  switch (shape % 5) {
    case 0:
      cv::circle(image, p, r, colour, cv::FILLED, cv::LINE_AA);
      break;
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
    default:
      cv::drawMarker(image, p, colour, cv::MARKER_CROSS, 2 * r + 3, 2, cv::LINE_AA);
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

cv::Mat DrawHitRatePlot(const EvaluationReport& report) {
  if (report.cells.empty()) throw std::invalid_argument("DrawHitRatePlot: the report is empty");
  std::vector<DescriptorVariant> variants;
  std::vector<std::string> distortions;
  std::vector<std::string> methods;
  std::vector<int> ns;
  for (const EvaluationCell& cell : report.cells) {
    AddOnce(variants, cell.variant);
    AddOnce(distortions, cell.distortion);
    AddOnce(methods, cell.method);
    AddOnce(ns, cell.n);
  }
  std::sort(ns.begin(), ns.end());

  const int columns = static_cast<int>(distortions.size());
  const int width = std::max(columns * kPanelWidth, 2 * kLegendEntryWidth);
  const int legend_per_row = std::max(1, width / kLegendEntryWidth);
  const int legend_rows = (static_cast<int>(methods.size()) + legend_per_row - 1) / legend_per_row;
  const int height = kTitleHeight + static_cast<int>(variants.size()) * kPanelHeight +
                     legend_rows * kLegendRowHeight + 12;
  cv::Mat image(height, width, CV_8UC3, kWhite);

  const int queries = report.cells.front().trials;
  PutCentred(image,
             "Top-1 hit rate vs query length n (" + std::to_string(queries) +
                 " queries per point, seed " + std::to_string(report.seed) + ", index " +
                 (report.search == SearchMode::kExact ? "exact" : "kdtree") + ")",
             width / 2, 26, 0.6, 1);

  const int plot_width = kPanelWidth - kMarginLeft - kMarginRight;
  const int plot_height = kPanelHeight - kMarginTop - kMarginBottom;
  const auto x_of = [&](int n, int left) {
    if (ns.size() == 1) return left + plot_width / 2;
    const double t = double(n - ns.front()) / double(ns.back() - ns.front());
    return left + static_cast<int>(std::lround(12 + t * (plot_width - 24)));
  };
  const auto y_of = [&](double rate, int top) {
    return top + static_cast<int>(std::lround((1.0 - rate) * plot_height));
  };

  for (std::size_t v = 0; v < variants.size(); ++v) {
    for (std::size_t d = 0; d < distortions.size(); ++d) {
      const int panel_x = static_cast<int>(d) * kPanelWidth;
      const int panel_y = kTitleHeight + static_cast<int>(v) * kPanelHeight;
      const int left = panel_x + kMarginLeft, top = panel_y + kMarginTop;
      const int right = left + plot_width, bottom = top + plot_height;

      PutCentred(image,
                 std::string(VariantName(variants[v])) + " / " + DistortionLabel(distortions[d]),
                 (left + right) / 2, panel_y + 22, 0.55, 1);
      for (int percent = 0; percent <= 100; percent += 20) {
        const int y = y_of(percent / 100.0, top);
        cv::line(image, {left, y}, {right, y}, kGrid, 1);
        const std::string label = std::to_string(percent);
        int baseline = 0;
        const cv::Size size = cv::getTextSize(label, kFont, 0.4, 1, &baseline);
        PutText(image, label, {left - 6 - size.width, y + size.height / 2}, 0.4);
      }
      for (int n : ns) {
        const int x = x_of(n, left);
        cv::line(image, {x, bottom}, {x, bottom + 4}, kBlack, 1);
        PutCentred(image, std::to_string(n), x, bottom + 18, 0.4);
      }
      cv::rectangle(image, {left, top}, {right, bottom}, kBlack, 1);
      PutCentred(image, "n (query frames)", (left + right) / 2, bottom + 40, 0.45);
      PutVertical(image, "hit rate (%)", {panel_x + 16, (top + bottom) / 2}, 0.45);

      for (std::size_t m = 0; m < methods.size(); ++m) {
        std::vector<cv::Point> points;
        for (int n : ns) {
          for (const EvaluationCell& cell : report.cells) {
            if (cell.variant == variants[v] && cell.distortion == distortions[d] &&
                cell.method == methods[m] && cell.n == n) {
              points.push_back({x_of(n, left), y_of(cell.hit_rate(), top)});
            }
          }
        }
        const cv::Scalar& colour = kPalette[m % kPalette.size()];
        cv::polylines(image, points, false, colour, 2, cv::LINE_AA);
        for (const cv::Point& p : points) DrawMarker(image, p, static_cast<int>(m), colour);
      }
    }
  }

  const int legend_top = kTitleHeight + static_cast<int>(variants.size()) * kPanelHeight + 4;
  const int legend_left =
      (width - std::min<int>(legend_per_row, static_cast<int>(methods.size())) * kLegendEntryWidth) / 2;
  for (std::size_t m = 0; m < methods.size(); ++m) {
    const int row = static_cast<int>(m) / legend_per_row, col = static_cast<int>(m) % legend_per_row;
    const int x = legend_left + col * kLegendEntryWidth;
    const int y = legend_top + row * kLegendRowHeight + kLegendRowHeight / 2;
    const cv::Scalar& colour = kPalette[m % kPalette.size()];
    cv::line(image, {x, y}, {x + 36, y}, colour, 2, cv::LINE_AA);
    DrawMarker(image, {x + 18, y}, static_cast<int>(m), colour);
    PutText(image, methods[m], {x + 44, y + 5}, 0.5);
  }
  return image;
}

void WriteHitRatePlot(const EvaluationReport& report, const std::string& path) {
  const cv::Mat image = DrawHitRatePlot(report);
  bool written = false;
  try {
    written = cv::imwrite(path, image, {cv::IMWRITE_PNG_COMPRESSION, 6});
  } catch (const cv::Exception& e) {
    throw std::runtime_error(path + ": cannot write the plot: " + e.what());
  }
  if (!written) throw std::runtime_error(path + ": cannot write the plot");
}

}  // namespace orbit
