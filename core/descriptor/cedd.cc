// CEDD extraction: grid, block sums, texture and colour per block, histogram, quantisation.
//
// Speed without giving up bit-exactness (docs/design.md#exactness): the reference sums
// per-pixel luminance Y = 0.114*B + 0.587*G + 0.299*R in doubles. Here 1000*Y is summed exactly as
// an integer from per-quadrant channel sums (Y is linear), which gives the exact quadrant mean as
// a fraction. The reference's rounding can only change the truncated mean when that exact mean is
// within its rounding error of an integer; for those few quadrants the reference's own
// double-precision sum is replayed pixel by pixel.
#include "core/descriptor/cedd.h"

#include "core/descriptor/appearance_channels.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

#include "core/descriptor/canonical_frame.h"
#include "core/descriptor/cedd_colour.h"
#include "core/descriptor/cedd_grid.h"
#include "core/descriptor/cedd_quantisation.h"
#include "core/descriptor/cedd_texture.h"

namespace orbit {
namespace {

using cedd::Grid;

// 1000 * Y per unit of each channel sum (Y = 0.114*B + 0.587*G + 0.299*R).
constexpr std::int64_t kLumaB = 114, kLumaG = 587, kLumaR = 299;

// Exact floor division of non-negative integers below 2^52 by a fixed divisor, by a multiply
// with the divisor's reciprocal and one correction step: the integer divisions it replaces were
// the largest cost per block.
class Divider {
 public:
  Divider() : Divider(1) {}
  explicit Divider(std::int64_t divisor) : divisor_(divisor), inverse_(1.0 / divisor) {}

  struct Result {
    std::int64_t quotient, remainder;
  };
  Result Divide(std::int64_t n) const {
    std::int64_t q = static_cast<std::int64_t>(static_cast<double>(n) * inverse_);
    std::int64_t r = n - q * divisor_;
    if (r < 0) {
      --q;
      r += divisor_;
    } else if (r >= divisor_) {
      ++q;
      r -= divisor_;
    }
    return {q, r};
  }
  std::int64_t divisor() const { return divisor_; }

 private:
  std::int64_t divisor_;
  double inverse_;
};

// Dividers by divisor, each built once: a cedd-full grid's cells and blocks come in only a few
// sizes (its edges are at floor(i * side / 40)), and building a Divider costs a floating-point
// division. Direct-mapped: a divisor that finds its slot taken simply replaces it.
class DividerCache {
 public:
  const Divider& operator()(std::int64_t divisor) {
    Slot& slot = slots_[static_cast<std::uint64_t>(divisor) % slots_.size()];
    if (slot.divisor != divisor) slot = {divisor, Divider(divisor)};
    return slot.divider;
  }

 private:
  struct Slot {
    std::int64_t divisor = 1;
    Divider divider;
  };
  std::array<Slot, 32> slots_;
};

// Brings any supported image to 8-bit BGR (a view, not a copy, when it already is).
cv::Mat ToBgr(const cv::Mat& region) {
  switch (region.type()) {
    case CV_8UC3: return region;
    case CV_8UC1: {
      cv::Mat bgr;
      cv::cvtColor(region, bgr, cv::COLOR_GRAY2BGR);
      return bgr;
    }
    case CV_8UC4: {
      // Composite over black: c' = round(c * a / 255). c*a/255 is never exactly k + 1/2
      // (255 is odd), so integer rounding with +127 is exact.
      cv::Mat bgr(region.rows, region.cols, CV_8UC3);
      for (int y = 0; y < region.rows; ++y) {
        const std::uint8_t* in = region.ptr<std::uint8_t>(y);
        std::uint8_t* out = bgr.ptr<std::uint8_t>(y);
        for (int x = 0; x < region.cols; ++x, in += 4, out += 3) {
          const int a = in[3];
          for (int c = 0; c < 3; ++c) out[c] = static_cast<std::uint8_t>((in[c] * a + 127) / 255);
        }
      }
      return bgr;
    }
    default:
      throw std::invalid_argument("CEDD needs an 8-bit BGR, grey or BGRA image, got OpenCV type " +
                                  std::to_string(region.type()));
  }
}

// The reference's truncated mean of a LIRE quadrant: (int)(sum of double Y * (4.0/(Sx*Sy))),
// with Y summed row by row in double precision exactly as LIRE does.
double ReplayLireQuadrantMean(const cv::Mat& bgr, int x0, int x1, int y0, int y1, int block_area) {
  double sum = 0;
  for (int y = y0; y < y1; ++y) {
    const std::uint8_t* p = bgr.ptr<std::uint8_t>(y) + 3 * x0;
    for (int x = x0; x < x1; ++x, p += 3) sum += (0.114 * p[0] + 0.587 * p[1] + 0.299 * p[2]);
  }
  return static_cast<int>(sum * (4.0 / block_area));
}

// Exact-arithmetic truncated quadrant mean on LIRE's grid (every quadrant has the same size),
// falling back to the replay when the reference's rounding could decide it (see the file comment).
class LireQuadrantMean {
 public:
  LireQuadrantMean(const cv::Mat& bgr, const Grid& grid, std::int64_t block_area)
      : bgr_(bgr),
        grid_(grid),
        block_area_(static_cast<int>(block_area)),
        luma_(1000 * (block_area / 4)),
        // The exact mean's distance to the nearest integer is remainder / divisor; replay when it
        // is within a generous bound on the reference's accumulated rounding error on the mean
        // (about 255 * pixels * 2^-53), i.e. 1e-12 * (pixels + 1).
        tolerance_(1e-15 * static_cast<double>(luma_.divisor() + 1000) *
                   static_cast<double>(luma_.divisor())) {}

  double operator()(const std::int64_t* cell, int col, int row) const {
    const std::int64_t luma1000 = kLumaB * cell[0] + kLumaG * cell[1] + kLumaR * cell[2];
    if (luma1000 == 0) return 0;  // every pixel black: every Y is exactly 0
    const auto [mean, remainder] = luma_.Divide(luma1000);
    const std::int64_t nearest = std::min(remainder, luma_.divisor() - remainder);
    if (remainder == 0 || static_cast<double>(nearest) <= tolerance_) {
      return ReplayLireQuadrantMean(bgr_, grid_.col_edges[col], grid_.col_edges[col + 1],
                                    grid_.row_edges[row], grid_.row_edges[row + 1], block_area_);
    }
    return static_cast<double>(mean);
  }

 private:
  const cv::Mat& bgr_;
  const Grid& grid_;
  int block_area_;
  Divider luma_;
  double tolerance_;
};

// cedd-full defines the quadrant mean as the exact truncated mean, with no floating point.
double ExactQuadrantMean(const std::int64_t* cell, const Divider& thousand_pixels) {
  const std::int64_t luma1000 = kLumaB * cell[0] + kLumaG * cell[1] + kLumaR * cell[2];
  return static_cast<double>(thousand_pixels.Divide(luma1000).quotient);
}

}  // namespace

Descriptor ExtractCedd(const cv::Mat& image, DescriptorVariant variant,
                       std::optional<cv::Rect> roi) {
  if (image.empty()) throw std::invalid_argument("CEDD of an empty image");
  const cv::Rect whole(0, 0, image.cols, image.rows);
  const cv::Rect area = roi.value_or(whole);
  if (area.width <= 0 || area.height <= 0 || (area & whole) != area) {
    throw std::invalid_argument("region of interest must be non-empty and inside the " +
                                std::to_string(image.cols) + "x" + std::to_string(image.rows) +
                                " image");
  }
  const bool canonical =
      variant == DescriptorVariant::kCeddRobust || HasAppearanceChannels(variant);
  const cv::Mat bgr = canonical ? CanonicalFrame(ToBgr(image(area))) : ToBgr(image(area));
  const bool lire = variant == DescriptorVariant::kCeddLire;
  const Grid grid = lire ? cedd::LireGrid(bgr.cols, bgr.rows) : cedd::FullGrid(bgr.cols, bgr.rows);

  Descriptor descriptor;
  descriptor.variant = variant;
  if (grid.empty()) return descriptor;

  const std::vector<std::int64_t> sums = cedd::CellSums(bgr, grid);
  const int cols = grid.cell_cols();
  auto cell_sums = [&](int col, int row) { return sums.data() + (row * cols + col) * 3; };
  auto cell_pixels = [&](int col, int row) {
    return static_cast<std::int64_t>(grid.col_edges[col + 1] - grid.col_edges[col]) *
           (grid.row_edges[row + 1] - grid.row_edges[row]);
  };

  // LIRE's blocks all have the same size; cedd-full's vary by a pixel.
  const std::int64_t lire_block_area = lire ? cell_pixels(grid.left[0], grid.top[0]) * 4 : 1;
  const LireQuadrantMean lire_quadrant_mean(bgr, grid, lire_block_area);
  const Divider lire_block(lire_block_area);
  DividerCache dividers;

  cedd::Histogram histogram = {};
  for (int by = 0; by < grid.blocks_y(); ++by) {
    const int rows[2] = {grid.top[by], grid.bottom[by]};
    const int row_count = rows[0] == rows[1] ? 1 : 2;
    for (int bx = 0; bx < grid.blocks_x(); ++bx) {
      const int columns[2] = {grid.left[bx], grid.right[bx]};
      const int column_count = columns[0] == columns[1] ? 1 : 2;

      // Block colour sums over its distinct cells.
      std::int64_t channel[3] = {0, 0, 0}, pixels = 0;
      for (int r = 0; r < row_count; ++r) {
        for (int c = 0; c < column_count; ++c) {
          const std::int64_t* s = cell_sums(columns[c], rows[r]);
          for (int k = 0; k < 3; ++k) channel[k] += s[k];
          pixels += cell_pixels(columns[c], rows[r]);
        }
      }

      double quadrant[4];  // top-left, top-right, bottom-left, bottom-right
      for (int q = 0; q < 4; ++q) {
        const int col = columns[q % 2], row = rows[q / 2];
        quadrant[q] =
            lire ? lire_quadrant_mean(cell_sums(col, row), col, row)
                 : ExactQuadrantMean(cell_sums(col, row), dividers(1000 * cell_pixels(col, row)));
      }
      const cedd::TextureClasses texture =
          cedd::ClassifyTexture({quadrant[0], quadrant[1], quadrant[2], quadrant[3]});

      // Mean colour with integer division (docs/design.md#colour-of-a-block).
      const Divider& block = lire ? lire_block : dividers(pixels);
      const cedd::Fuzzy24 colour =
          cedd::FuzzyColour(static_cast<int>(block.Divide(channel[2]).quotient),
                            static_cast<int>(block.Divide(channel[1]).quotient),
                            static_cast<int>(block.Divide(channel[0]).quotient));
      // The reference adds only bins > 0; colour bins are never negative and adding +0.0 leaves
      // a sum unchanged, so adding all 24 unconditionally is bit-identical (and vectorises).
      for (int t = 0; t < texture.count; ++t) {
        double* bins = histogram + kColourBins * texture.classes[t];
        for (int j = 0; j < kColourBins; ++j) bins[j] += colour[j];
      }
    }
  }
  descriptor.values = cedd::Quantise(histogram);
  if (HasAppearanceChannels(variant)) AddAppearanceChannels(bgr, variant, descriptor.values);
  return descriptor;
}

}  // namespace orbit
