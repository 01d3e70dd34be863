// EstimateNoiseSigma: how much Gaussian-like noise a frame carries, in grey levels, cheaply
// enough to run on every frame on the device (a frame's quality reading, which the calibrated
// rule's allowance for noisy frames reads).
//
// Immerkær's estimator (J. Immerkær, "Fast noise variance estimation", CVIU 64(2), 1996): the
// image is convolved with the 3x3 mask N = [1 -2 1; -2 4 -2; 1 -2 1], the difference of two
// Laplacians, which cancels smooth intensity (planes and most of an edge) and keeps noise; for
// independent noise of deviation s, E|I * N| = s * 6 * sqrt(2 / pi), so
//   s = sqrt(pi / 2) / (6 (W - 2) (H - 2)) * sum over the inner pixels of |I * N|.
// Each channel is estimated on its own and the channels' estimates averaged, so noise added
// channel by channel (the evaluation's gn, a camera's sensor) is read at its own deviation.
// Texture and sharp edges read as a little noise (COIL-100's clean views: 1-2 grey levels);
// where values are clipped at 0 or 255 (a black background) the noise is partly gone and reads
// lower. Pure and thread-safe.
#pragma once

#include <opencv2/core.hpp>

namespace orbit {

// The estimated deviation of the noise of `image` (8-bit, 1, 3 or 4 channels; a 4th channel,
// alpha, is ignored), in grey levels (0..255 scale). Returns 0 for an image smaller than 3 x 3.
// Throws std::invalid_argument for an empty image or one of another type. Integer arithmetic,
// one pass over the pixels.
double EstimateNoiseSigma(const cv::Mat& image);

}  // namespace orbit
