#include "bench/synthetic_objects.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/descriptor/appearance_channels.h"

namespace orbit::bench {

namespace {

// Bins of unequal popularity: a shuffled exponential decay over `size` bins.
std::discrete_distribution<int> PopularBins(int size, double decay, std::mt19937& random) {
  std::vector<double> popularity(size);
  for (int bin = 0; bin < size; ++bin) popularity[bin] = std::exp(-bin / decay);
  std::shuffle(popularity.begin(), popularity.end(), random);
  return std::discrete_distribution<int>(popularity.begin(), popularity.end());
}

}  // namespace

SyntheticObjects::SyntheticObjects(int objects, DescriptorVariant variant)
    : variant_(variant), random_(20240611) {
  bins_ = PopularBins(kCeddSize, 30.0, random_);
  if (HasAppearanceChannels(variant_))
    colour_bins_ = PopularBins(kColourChannelSize, 40.0, random_);
  for (int o = 0; o < objects; ++o) {
    keyframes_.push_back({Keyframe(), Keyframe(), Keyframe()});
  }
}

DescriptorValues SyntheticObjects::View(int o, double azimuth) {
  const double position = azimuth / 120.0;
  const int first = static_cast<int>(std::floor(position)) % 3;
  const double t = position - std::floor(position);
  const auto& a = keyframes_[o][first];
  const auto& b = keyframes_[o][(first + 1) % 3];
  std::bernoulli_distribution jitter(0.1), up(0.5);
  DescriptorValues view{};
  const int size = HasAppearanceChannels(variant_) ? kDescriptorSize : kCeddSize;
  for (int i = 0; i < size; ++i) {
    int value = static_cast<int>(std::lround((1 - t) * a[i] + t * b[i]));
    if (value > 0 && jitter(random_)) value += up(random_) ? 1 : -1;
    view[i] = static_cast<std::uint8_t>(std::clamp(value, 0, kDescriptorMaxValue));
  }
  return view;
}

ObjectModel SyntheticObjects::Model(int o) {
  ObjectModel model;
  model.id = o + 1;
  model.name = "synthetic" + std::to_string(o + 1);
  model.variant = variant_;
  for (int v = 0; v < kViewsPerObject; ++v) {
    ModelView view;
    view.descriptor = View(o, v * 5.0);
    view.azimuth = v * 5.0;
    view.typical_distance = 0.2;
    model.views.push_back(view);
  }
  return model;
}

std::vector<ObjectModel> SyntheticObjects::Models() {
  std::vector<ObjectModel> models;
  for (int o = 0; o < object_count(); ++o) models.push_back(Model(o));
  return models;
}

std::vector<QueryFrame> SyntheticObjects::Frames(int o, double start, int count) {
  std::vector<QueryFrame> frames;
  for (int k = 0; k < count; ++k) {
    const double azimuth = std::fmod(start + 2.5 + 10.0 * k, 360.0);
    frames.push_back({{variant_, View(o, azimuth)}, azimuth + 33.0});
  }
  return frames;
}

DescriptorValues SyntheticObjects::Keyframe() {
  // Values 1..7 with COIL-100's proportions (53% ones, 20% twos, ...).
  std::discrete_distribution<int> value({0, 53, 20, 10, 5, 4.5, 5, 2});
  DescriptorValues keyframe{};
  for (int n = 0; n < 21; ++n) keyframe[bins_(random_)] = static_cast<std::uint8_t>(value(random_));
  if (!HasAppearanceChannels(variant_)) return keyframe;
  // COIL-100's proportions in cedd-hsv-hog (36 views of 9 objects: 12% ones, 17% twos, ...).
  std::discrete_distribution<int> colour_value({0, 12, 17, 18, 13, 15, 8, 17});
  for (int n = 0; n < 34; ++n) {
    keyframe[kColourChannelOffset + colour_bins_(random_)] =
        static_cast<std::uint8_t>(colour_value(random_));
  }
  std::uniform_int_distribution<int> cell_orientation(0, kGradientChannelSize - 1);
  for (int n = 0; n < 47; ++n) keyframe[kGradientChannelOffset + cell_orientation(random_)] = 1;
  return keyframe;
}

}  // namespace orbit::bench
