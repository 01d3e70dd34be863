// SyntheticObjects: a seeded catalogue of objects whose views resemble COIL-100's CEDDs, for the
// speed benchmarks (engines, candidates, scale): every run sees the same sets.
//
// About 21 non-zero bins of 144, values mostly 1-2, bins of unequal popularity: each object has
// three keyframe descriptors around the circle and its view at azimuth a blends the two nearest
// keyframes, with +-1 jitter on some bins. Models hold kViewsPerObject views 5 degrees apart.
// In a variant with appearance channels (cedd-hsv-hog, the product's), each keyframe also holds
// about 34 non-zero colour bins of 192, values 1-7 spread as COIL-100's, and about 47 non-zero
// gradient values of 144, each 1, as COIL-100's (the channels' values are scaled to small norms:
// core/descriptor/appearance_channels.h).
#pragma once

#include <array>
#include <random>
#include <vector>

#include "core/descriptor/descriptor.h"
#include "core/descriptor/query_frame.h"
#include "core/model/object_model.h"

namespace orbit::bench {

constexpr int kViewsPerObject = 72;

class SyntheticObjects {
 public:
  explicit SyntheticObjects(int objects, DescriptorVariant variant = DescriptorVariant::kCeddLire);

  int object_count() const { return static_cast<int>(keyframes_.size()); }

  // View of object o (0-based) at azimuth a (degrees), blended from the keyframes with jitter.
  DescriptorValues View(int o, double azimuth);

  // Object o's model: id o + 1, name "synthetic<o + 1>", kViewsPerObject views.
  ObjectModel Model(int o);
  // Every object's model.
  std::vector<ObjectModel> Models();

  // A sequence of frames of one object, 10 degrees apart, starting between two model views.
  std::vector<QueryFrame> Frames(int o, double start, int count);

 private:
  DescriptorValues Keyframe();

  DescriptorVariant variant_;
  std::mt19937 random_;
  std::discrete_distribution<int> bins_;
  std::discrete_distribution<int> colour_bins_;  // of the colour channel's 192
  std::vector<std::array<DescriptorValues, 3>> keyframes_;
};

}  // namespace orbit::bench
