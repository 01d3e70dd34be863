// build/orbit_robustness_ablation: what each step of the canonical frame
// (core/descriptor/canonical_frame.h) contributes to recognising degraded frames, one step switched
// on or off at a time (docs/results/robustness.md, "Ablation").
//
//   orbit_robustness_ablation COIL_DIR [OBJECTS] [DISTORTION ...]
//
// OBJECTS is a range as `orbit eval --objects` takes it (default 1-50: the objects the product
// was tuned on); DISTORTIONs are eval's specs (evaluation/distortion_spec.h; default: a spread
// of blur, noise, compression, gain and resolution). For each configuration, every view of the
// objects is a model view and every third view a single-frame query under each distortion,
// matched to its nearest model view by Tanimoto similarity (EIS at n = 1, docs/design.md#eis), the
// query's own view and its neighbours within 10 degrees left out as the protocol leaves them
// out. Prints one Markdown row per configuration: the top-1 hit rate per distortion, the mean
// and the worst. Noise is seeded per image: reruns print the same table.
#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "client/image_file.h"
#include "core/base/parallel_for.h"
#include "core/base/seeded_random.h"
#include "core/descriptor/canonical_frame.h"
#include "core/descriptor/cedd.h"
#include "core/descriptor/similarity.h"
#include "evaluation/dataset.h"
#include "evaluation/distortion_spec.h"

namespace {

using namespace orbit;

struct Configuration {
  std::string name;
  CanonicalFrameOptions frame;
  std::vector<std::string> augmentation;  // distortions of each model view stored beside it
};

std::vector<Configuration> Configurations() {
  const CanonicalFrameOptions product;
  const auto with = [&](int area, double blur, bool brightness) {
    return CanonicalFrameOptions{area, blur, brightness};
  };
  return {
      {"none (cedd-full)", with(0, 0, false), {}},
      {"canonical size only", with(kCanonicalArea, 0, false), {}},
      {"size + blur 1 px", with(kCanonicalArea, 1, false), {}},
      {"size + blur 2 px", with(kCanonicalArea, 2, false), {}},
      {"size + blur 3 px", with(kCanonicalArea, 3, false), {}},
      {"size + brightness", with(kCanonicalArea, 0, true), {}},
      {"size + blur 1.5 px + brightness", with(kCanonicalArea, 1.5, true), {}},
      {"**cedd-robust**: size + blur 2 px + brightness", product, {}},
      {"size + blur 2.5 px + brightness", with(kCanonicalArea, 2.5, true), {}},
      {"none + augmentation (noisy, blurred copy)",
       with(0, 0, false),
       {"gn:var=0.006", "mb:len=10:angle=45"}},
      {"cedd-robust + augmentation (noisy, blurred copy)",
       product,
       {"gn:var=0.006", "mb:len=10:angle=45"}},
  };
}

const std::vector<std::string> kDefaultDistortions = {"df",
                                                      "mb:len=5:angle=60",
                                                      "mb:len=15:angle=20",
                                                      "mb:len=25:angle=130",
                                                      "gn:var=0.002",
                                                      "gn:var=0.012",
                                                      "gn:var=0.03",
                                                      "jpeg:q=10",
                                                      "jpeg:q=40",
                                                      "gain:0.6",
                                                      "gain:1.4",
                                                      "lowres:0.5",
                                                      "mb:len=9:angle=70+gn:var=0.004"};

struct DescribedView {
  int object = 0;
  double azimuth = 0;
  DescriptorValues descriptor{};
};

DescriptorValues Describe(const cv::Mat& image, const CanonicalFrameOptions& frame) {
  return ExtractCedd(CanonicalFrame(image, frame), DescriptorVariant::kCeddFull).values;
}

// Hit rates (%) per distortion of one configuration.
std::vector<double> Evaluate(const std::vector<DatasetImage>& images,
                             const std::vector<DistortionSpec>& distortions,
                             const Configuration& configuration) {
  std::vector<DistortionSpec> augmentation;
  for (const std::string& spec : configuration.augmentation) {
    augmentation.push_back(ParseDistortionSpec(spec));
  }
  const std::vector<DatasetObject> objects = GroupByObject(images);
  std::vector<int> object_of(images.size());
  for (std::size_t o = 0; o < objects.size(); ++o) {
    for (std::size_t i : objects[o].images) object_of[i] = static_cast<int>(o);
  }
  std::vector<std::vector<DescribedView>> models(images.size());
  std::vector<std::vector<DescriptorValues>> queries(images.size());
  std::atomic<std::size_t> done{0};
  ParallelFor(images.size(), 0, [&](std::size_t i) {
    const cv::Mat image = ReadImageFile(images[i].path);
    const DescribedView view{object_of[i], images[i].azimuth, {}};
    models[i].push_back(view);
    models[i].back().descriptor = Describe(image, configuration.frame);
    for (std::size_t a = 0; a < augmentation.size(); ++a) {
      models[i].push_back(view);
      models[i].back().descriptor = Describe(
          ApplyDistortion(image, augmentation[a], MixSeed(7, i * 16 + a)), configuration.frame);
    }
    if (i % 3 == 0) {
      for (std::size_t d = 0; d < distortions.size(); ++d) {
        queries[i].push_back(Describe(
            ApplyDistortion(image, distortions[d], MixSeed(11, i * 64 + d)), configuration.frame));
      }
    }
    const std::size_t finished = ++done;
    if (finished % 500 == 0)
      std::fprintf(stderr, "\r  %s: %zu / %zu images", configuration.name.c_str(), finished,
                   images.size());
  });
  std::fprintf(stderr, "\n");
  std::vector<DescribedView> views;
  for (const auto& m : models) views.insert(views.end(), m.begin(), m.end());

  std::vector<std::vector<char>> hits(images.size());
  ParallelFor(images.size(), 0, [&](std::size_t i) {
    for (const DescriptorValues& query : queries[i]) {
      double best = -1;
      int answer = -1;
      for (const DescribedView& view : views) {
        if (view.object == object_of[i]) {
          const double gap = std::abs(std::remainder(view.azimuth - images[i].azimuth, 360.0));
          if (gap <= 10 + 1e-9) continue;  // the protocol's exclusion
        }
        const double similarity = Tanimoto(query, view.descriptor);
        if (similarity > best) {
          best = similarity;
          answer = view.object;
        }
      }
      hits[i].push_back(answer == object_of[i]);
    }
  });
  std::vector<double> rates(distortions.size(), 0);
  int count = 0;
  for (const auto& h : hits) {
    if (h.empty()) continue;
    ++count;
    for (std::size_t d = 0; d < h.size(); ++d) rates[d] += h[d];
  }
  for (double& rate : rates) rate = 100.0 * rate / count;
  return rates;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
    std::fprintf(stderr,
                 "usage: %s COIL_DIR [OBJECTS (default 1-50)] [DISTORTION ...]\n"
                 "Single-frame hit rate of each canonical-frame configuration under each "
                 "distortion (Markdown).\n",
                 argv[0]);
    return argc < 2 ? 2 : 0;
  }
  try {
    const std::string range = argc > 2 ? argv[2] : "1-50";
    std::vector<std::string> names(argv + std::min(argc, 3), argv + argc);
    if (names.empty()) names = kDefaultDistortions;
    std::vector<DistortionSpec> distortions;
    for (const std::string& name : names) distortions.push_back(ParseDistortionSpec(name));
    const std::vector<DatasetImage> images = ListCoil100(argv[1], ParseObjectRange(range));

    std::printf("Objects %s; every third view a query; n = 1, nearest view (eis).\n\n",
                range.c_str());
    std::printf("| configuration |");
    for (const DistortionSpec& d : distortions) std::printf(" %s |", d.name.c_str());
    std::printf(" mean | worst |\n|---|");
    for (std::size_t d = 0; d < distortions.size() + 2; ++d) std::printf("---:|");
    std::printf("\n");
    for (const Configuration& configuration : Configurations()) {
      const std::vector<double> rates = Evaluate(images, distortions, configuration);
      double sum = 0, worst = 100;
      std::printf("| %s |", configuration.name.c_str());
      for (double rate : rates) {
        std::printf(" %.1f |", rate);
        sum += rate;
        worst = std::min(worst, rate);
      }
      std::printf(" %.1f | %.1f |\n", sum / rates.size(), worst);
      std::fflush(stdout);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "orbit_robustness_ablation: %s\n", e.what());
    return 1;
  }
  return 0;
}
