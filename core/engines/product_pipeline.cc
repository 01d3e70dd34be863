#include "core/engines/product_pipeline.h"

#include <sstream>

#include "core/descriptor/appearance_channels.h"
#include "core/descriptor/canonical_frame.h"

namespace orbit {

int ProductCandidatesAbove(DescriptorVariant variant) {
  return HasAppearanceChannels(variant) ? kProductCandidatesAbove : kCeddCandidatesAbove;
}

double ProductFalseAcceptRate(DescriptorVariant variant) {
  return variant == DescriptorVariant::kCeddHsvLayout ? kLayoutFalseAcceptRate
                                                      : kProductFalseAcceptRate;
}

std::string DescribeProductFalseAcceptRates() {
  std::ostringstream text;
  text << kProductFalseAcceptRate << ", " << kLayoutFalseAcceptRate << " on "
       << VariantName(DescriptorVariant::kCeddHsvLayout);
  return text.str();
}

const ProductPipeline& Product() {
  static const ProductPipeline product;
  return product;
}

std::string DescribeProduct() {
  const ProductPipeline& p = Product();
  std::ostringstream text;
  text << p.engine << " (" << p.options.hmm_states << " states, window " << p.options.window
       << ", emissions to the power " << (1 << p.options.hmm_sharpness) << ", ";
  if (p.options.nearest_view_weight == 1) {
    text << "the path's best " << RankedDepth(p.options)
         << " objects scored by their nearest and blended views";
  } else {
    text << "score " << 1 - p.options.nearest_view_weight << " path + "
         << p.options.nearest_view_weight << " nearest views";
  }
  text << ") on " << VariantName(p.variant) << " (CEDD of a canonical frame: resampled to "
       << kCanonicalArea << " pixels, Gaussian blur of " << kCanonicalBlurSigma
       << " px, brightness scaled so that the " << kBrightnessPercentile * 100
       << "th percentile of the brightest channel is " << kBrightnessTarget;
  if (HasAppearanceChannels(p.variant)) {
    if (p.variant != DescriptorVariant::kCeddHsvLayout) {
      text << "; then a " << kHueBins << " x " << kSaturationBins << " x " << kValueBins
           << " hue-saturation-value histogram of the object's colours";
      if (p.variant == DescriptorVariant::kCeddSoftHsvHog) {
        text << " (a hue within " << kHueEdgeReach
             << " of a bin's width of its edge shared with the bin beyond)";
      }
    } else {
      text << "; then " << kHueBins << " x " << kLayoutSaturationBins << " x " << kValueBins
           << " hue-saturation-value histograms of the object's colours in the frame's upper "
              "and lower halves";
    }
    text << ", its background's taken off, and " << kGradientCellsPerSide << " x "
         << kGradientCellsPerSide << " cells of " << kGradientOrientations
         << " gradient orientations";
  }
  text << ")";
  if (p.options.candidate_objects > 0) {
    text << "; above " << p.options.candidates_above << " objects, each frame scores the "
         << p.options.candidate_objects << " objects whose sector summaries are most like it";
  }
  return text.str();
}

}  // namespace orbit
