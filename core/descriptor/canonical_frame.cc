#include "core/descriptor/canonical_frame.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "core/base/cpu_dispatch.h"
#include "core/descriptor/column_sums.h"

namespace orbit {
namespace {

// floor(n / d) for 0 <= n < 512 * d and 0 < d < 2^19, by a multiply and a shift instead of a
// division: with m = floor(2^48 / d) + 1, n * m / 2^48 exceeds n / d by at most n / 2^48, which
// is below 1 / d (n * d < 2^47): too little to reach the next integer. n * m stays below 2^64.
class BlockDivider {
 public:
  static constexpr std::uint32_t kMaxDivisor = 1u << 19;
  explicit BlockDivider(std::uint32_t d) : multiplier_((std::uint64_t{1} << 48) / d + 1) {}
  std::uint32_t operator()(std::uint32_t n) const {
    return static_cast<std::uint32_t>((n * multiplier_) >> 48);
  }

 private:
  std::uint64_t multiplier_;
};

// The mean of every k x k block of `bgr` (k >= 2), rounded; rows and columns past the last
// whole block are left out (fewer than k of them). What INTER_AREA computes for an integer
// factor, as two passes of integer additions: k rows summed into one (vectorised), then k
// pixels of that sum into one. OpenCV's INTER_AREA takes several times longer on 3 channels.
cv::Mat BlockMeans(const cv::Mat& bgr, int k) {
  const int width = bgr.cols / k, height = bgr.rows / k;
  const std::size_t span = static_cast<std::size_t>(width) * k * 3;  // bytes of whole blocks
  const std::uint32_t area = static_cast<std::uint32_t>(k * k);
  cv::Mat out(height, width, CV_8UC3);
  // One row of blocks: its k rows summed into `sums`, then each block's k columns.
  const auto block_row = [&](int y, auto& sums, const auto& divide) {
    using Sum = typename std::decay_t<decltype(sums)>::value_type;
    std::fill(sums.begin(), sums.end(), Sum{0});
    for (int dy = 0; dy < k; ++dy) {
      RunHotLoop<AddRowToColumnSums<Sum>>(bgr.ptr<std::uint8_t>(y * k + dy), sums.data(), span);
    }
    std::uint8_t* row = out.ptr<std::uint8_t>(y);
    const Sum* block = sums.data();
    for (int x = 0; x < width; ++x, block += 3 * k) {
      for (int c = 0; c < 3; ++c) {
        std::uint32_t sum = area / 2;
        for (int dx = 0; dx < k; ++dx) sum += block[dx * 3 + c];
        row[x * 3 + c] = static_cast<std::uint8_t>(divide(sum));
      }
    }
  };
  // 16-bit sums (twice the lanes per vector) while k rows cannot overflow them: 16 x 255.
  std::vector<std::uint16_t> narrow(k <= 16 ? span : 0);
  std::vector<std::uint32_t> wide(k > 16 ? span : 0);
  const auto by_division = [area](std::uint32_t n) { return n / area; };
  const BlockDivider by_multiply(area < BlockDivider::kMaxDivisor ? area : 1);
  for (int y = 0; y < height; ++y) {
    if (k <= 16) {
      block_row(y, narrow, by_multiply);
    } else if (area < BlockDivider::kMaxDivisor) {
      block_row(y, wide, by_multiply);
    } else {
      block_row(y, wide, by_division);
    }
  }
  return out;
}

// Step 2 as OpenCV's GaussianBlur computes it for an 8-bit image and deviation kCanonicalBlurSigma
// (docs/design.md#canonical-frame): a fixed-point kernel of 13 taps in 1/256 units along each
// axis, the border reflected without repeating the edge pixel, the exact integer sum of both
// passes rounded once, half up. The same sums in the same integers give the same image, bit for
// bit (CanonicalFrameTest compares the two); OpenCV's general path takes several times longer on
// 3 channels.
constexpr int kBlurRadius = 6;
// The taps from the centre out: 1, 2, 7, 16, 31, 45, 52, 45, ... 1, summing to 256.
constexpr std::array<std::uint32_t, kBlurRadius + 1> kBlurKernel = {52, 45, 31, 16, 7, 2, 1};

// One row, horizontally: padded holds the row with kBlurRadius reflected pixels on each side.
ORBIT_HOT_LOOP void BlurRow(const std::uint8_t* __restrict padded, std::uint16_t* __restrict out,
                            int n, int channels) {
  const std::uint8_t* centre = padded + kBlurRadius * channels;
  for (int i = 0; i < n; ++i) {  // 16-bit lanes suffice: the sum is at most 255 * 256
    std::uint16_t sum = static_cast<std::uint16_t>(kBlurKernel[0] * centre[i]);
    for (int t = 1; t <= kBlurRadius; ++t) {
      sum = static_cast<std::uint16_t>(
          sum + kBlurKernel[t] * (centre[i - t * channels] + centre[i + t * channels]));
    }
    out[i] = sum;
  }
}

// One output row, vertically: rows[t] is the horizontally blurred row t - kBlurRadius away.
ORBIT_HOT_LOOP void BlurColumn(const std::uint16_t* const* rows, std::uint8_t* __restrict out,
                               int n) {
  const std::uint16_t* centre = rows[kBlurRadius];
  for (int i = 0; i < n; ++i) {
    std::uint32_t sum = kBlurKernel[0] * centre[i] + (1u << 15);
    for (int t = 1; t <= kBlurRadius; ++t) {
      sum += kBlurKernel[t] * (std::uint32_t{rows[kBlurRadius - t][i]} + rows[kBlurRadius + t][i]);
    }
    out[i] = static_cast<std::uint8_t>(sum >> 16);
  }
}

// Index i of a line of n > kBlurRadius pixels, reflected at the ends without repeating them.
int Reflect(int i, int n) { return i < 0 ? -i : i >= n ? 2 * (n - 1) - i : i; }

// Step 2 with the canonical deviation, for images wider and taller than kBlurRadius (smaller ones
// reflect more than once, which OpenCV handles).
cv::Mat CanonicalBlur(const cv::Mat& bgr) {
  const int width = bgr.cols, height = bgr.rows, channels = 3, n = width * channels;
  std::vector<std::uint16_t> horizontal(static_cast<std::size_t>(height) * n);
  std::vector<std::uint8_t> padded(static_cast<std::size_t>(width + 2 * kBlurRadius) * channels);
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* in = bgr.ptr<std::uint8_t>(y);
    std::copy(in, in + n, padded.begin() + kBlurRadius * channels);
    for (int t = 1; t <= kBlurRadius; ++t) {
      std::copy_n(in + Reflect(-t, width) * channels, channels,
                  padded.begin() + (kBlurRadius - t) * channels);
      std::copy_n(in + Reflect(width - 1 + t, width) * channels, channels,
                  padded.begin() + (kBlurRadius + width - 1 + t) * channels);
    }
    RunHotLoop<BlurRow>(padded.data(), horizontal.data() + static_cast<std::size_t>(y) * n, n,
                        channels);
  }
  cv::Mat out(height, width, CV_8UC3);
  std::array<const std::uint16_t*, 2 * kBlurRadius + 1> rows;
  for (int y = 0; y < height; ++y) {
    for (int t = 0; t <= 2 * kBlurRadius; ++t) {
      rows[t] =
          horizontal.data() + static_cast<std::size_t>(Reflect(y + t - kBlurRadius, height)) * n;
    }
    RunHotLoop<BlurColumn>(rows.data(), out.ptr<std::uint8_t>(y), n);
  }
  return out;
}

// Step 1: resampled to about `area` pixels, aspect ratio kept: area averaging when shrinking
// (by whole blocks first when the factor is 2 or more, then bilinear for the rest), bilinear
// when growing.
cv::Mat CanonicalSize(const cv::Mat& bgr, int area) {
  if (area <= 0) return bgr.clone();
  const double scale = std::sqrt(double(area) / (double(bgr.cols) * bgr.rows));
  const int width = std::max(1, static_cast<int>(std::lround(bgr.cols * scale)));
  const int height = std::max(1, static_cast<int>(std::lround(bgr.rows * scale)));
  if (width == bgr.cols && height == bgr.rows) return bgr.clone();
  const int block = static_cast<int>(1 / scale);
  if (block >= 2 && bgr.cols / block >= width && bgr.rows / block >= height) {
    cv::Mat blocks = BlockMeans(bgr, block);
    if (blocks.cols == width && blocks.rows == height) return blocks;
    // Less than a factor 2 is left: bilinear is as good there and faster than INTER_AREA.
    cv::Mat resized;
    cv::resize(blocks, resized, cv::Size(width, height), 0, 0, cv::INTER_LINEAR);
    return resized;
  }
  cv::Mat resized;
  cv::resize(bgr, resized, cv::Size(width, height), 0, 0,
             scale < 1 ? cv::INTER_AREA : cv::INTER_LINEAR);
  return resized;
}

// Step 3, in place.
void NormaliseBrightness(cv::Mat& bgr) {
  std::array<int, 256> histogram{};  // of the brightest channel, over every pixel
  for (int y = 0; y < bgr.rows; ++y) {
    const std::uint8_t* p = bgr.ptr<std::uint8_t>(y);
    for (int x = 0; x < bgr.cols; ++x, p += 3) ++histogram[std::max({p[0], p[1], p[2]})];
  }
  int bright = 0;  // pixels above kDarkLevel
  for (int v = kDarkLevel + 1; v < 256; ++v) bright += histogram[v];
  if (bright == 0 || bright * 100 < bgr.rows * bgr.cols) return;
  // The smallest value v with at least kBrightnessPercentile of the bright pixels at or below v.
  const double wanted = kBrightnessPercentile * bright;
  int below = 0, percentile = kDarkLevel + 1;
  for (int v = kDarkLevel + 1; v < 256; ++v) {
    below += histogram[v];
    if (below >= wanted) {
      percentile = v;
      break;
    }
  }
  bgr.convertTo(bgr, CV_8UC3, double(kBrightnessTarget) / percentile);
}

}  // namespace

cv::Mat CanonicalFrame(const cv::Mat& bgr, const CanonicalFrameOptions& options) {
  if (bgr.empty() || bgr.type() != CV_8UC3) {
    throw std::invalid_argument("CanonicalFrame needs a non-empty 8-bit BGR image, got type " +
                                std::to_string(bgr.type()) + " of " + std::to_string(bgr.cols) +
                                "x" + std::to_string(bgr.rows));
  }
  cv::Mat frame = CanonicalSize(bgr, options.area);
  if (options.blur_sigma == kCanonicalBlurSigma && frame.cols > kBlurRadius &&
      frame.rows > kBlurRadius) {
    frame = CanonicalBlur(frame);
  } else if (options.blur_sigma > 0) {
    cv::GaussianBlur(frame, frame, cv::Size(0, 0), options.blur_sigma);
  }
  if (options.normalise_brightness) NormaliseBrightness(frame);
  return frame;
}

}  // namespace orbit
