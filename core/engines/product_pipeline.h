// The product's default recognition pipeline, defined once (docs/design.md#product-pipeline): the
// descriptor variant a device describes its frames in and a server keeps its models in, the engine
// a session runs when it asks for none, and that engine's options. `orbit serve` takes its defaults
// from here, the client library describes frames in its server's variant, and `orbit eval --methods
// product` evaluates exactly this, so the three cannot drift apart.
//
// Why these choices: docs/results/robustness.md (the tables, the ablation, the commands) and
// docs/results/real-objects.md (the variant).
#pragma once

#include <string>
#include <string_view>

#include "core/descriptor/descriptor.h"
#include "core/engines/engine_options.h"

namespace orbit {

// The method name `orbit eval` gives the product pipeline.
inline constexpr std::string_view kProductMethod = "product";

// Above some number of objects a session scores only the objects the index proposes,
// kProductCandidateObjects per frame (EngineOptions::candidate_objects), where scoring every
// object's sector table costs more than proposing candidates. That table's cost grows with the
// frame's non-zero values: a variant with appearance channels (whose gradient cells are dense)
// crosses over at kProductCandidatesAbove objects, the CEDD-only variants (a few dozen non-zero
// bins) at kCeddCandidatesAbove. Why these: docs/design.md#object-candidates.
inline constexpr int kProductCandidateObjects = 8;
inline constexpr int kProductCandidatesAbove = 500;
inline constexpr int kCeddCandidatesAbove = 5000;

// The candidates_above of the product's engine on a model set in `variant`.
int ProductCandidatesAbove(DescriptorVariant variant);

// The calibrated rule's target false-accept rate (EngineOptions::false_accept_rate) of the
// product's engine on a model set in `variant`. Each variant's unknown statistic spreads its own
// way over the same objects, so each has its own target, chosen by one rule: the largest rate at
// which every goal of the tuning split holds (docs/design.md#target-rate). The colour layout's
// is kLayoutFalseAcceptRate; every other variant's kProductFalseAcceptRate.
inline constexpr double kProductFalseAcceptRate = 0.15;
inline constexpr double kLayoutFalseAcceptRate = 0.09;
double ProductFalseAcceptRate(DescriptorVariant variant);
// The rates above in words, for --help and the server's account: "0.15, 0.09 on cedd-hsv-layout".
std::string DescribeProductFalseAcceptRates();

struct ProductPipeline {
  DescriptorVariant variant = DescriptorVariant::kCeddSoftHsvHog;
  std::string_view engine = "hmm";  // one of EngineNames()
  // The engine's options: EngineOptions' defaults but for the HMM's sharpened emissions
  // (hmm_sharpness 5: emissions to the 32nd power), with which using the measured turns no
  // longer costs the right object points against ignoring them; the best objects of the path
  // scored by their nearest views and blended views alone (nearest_view_weight 1: the sector
  // means miss what single views show, and between enrolled views the blends show it,
  // docs/design.md#nearest-view-blend); the calibrated accept / unknown rule; and move
  // suggestions that never send the device back to a side it has seen while the other is new
  // (docs/results/recognition.md).
  EngineOptions options = [](DescriptorVariant variant) {
    EngineOptions options;
    options.hmm_sharpness = kMaxHmmSharpness;
    options.nearest_view_weight = 1;
    options.rejection = RejectionRule::kCalibrated;
    options.move_prefers_new_side = true;
    options.candidate_objects = kProductCandidateObjects;
    options.candidates_above = ProductCandidatesAbove(variant);
    options.false_accept_rate = ProductFalseAcceptRate(variant);
    return options;
  }(variant);
};

// The pipeline above.
const ProductPipeline& Product();

// One line saying what the product pipeline is, for reports and --help, e.g.
// "hmm (8 states, window 8, ...) on cedd-hsv-hog (CEDD of a canonical frame: ...; then a
// 12 x 4 x 4 hue-saturation-value histogram ...)".
std::string DescribeProduct();

}  // namespace orbit
