// EngineOptions: what an engine is run with, every field's default and its range, each range
// checked in one place (ValidateEngineOptions) with one message. The server, `orbit eval` and the
// device's requests all reach an engine through this check (docs/design.md#engines).
#pragma once

#include <string_view>

#include "core/decision/rejection.h"

namespace orbit {

// The ranges' ends.
inline constexpr int kMaxWindow = 64;
inline constexpr int kMaxTopK = 100;
inline constexpr int kMaxListLength = 64;
// Sectors of 1 degree at the finest: more states than degrees would hold empty sectors only.
inline constexpr int kMaxHmmStates = 360;
inline constexpr int kMaxHmmSharpness = 5;  // emissions up to the 32nd power
// w, per radian: at most this. A turn of 1 degree then already costs 17 similarity points, so
// larger weights change nothing but can overflow a score to infinity.
inline constexpr double kMaxOrientationWeight = 1000;
inline constexpr int kMaxAveragedViews = 360;
inline constexpr int kMaxCandidateObjects = 4096;
inline constexpr int kMaxCandidatesAbove = 1'000'000'000;

// Symbols as in docs/design.md; the product's values are in core/engines/product_pipeline.h.
struct EngineOptions {
  int window = 8;                   // W: frames kept (1..kMaxWindow)
  int list_length = 4;              // N_L: views per VCI retrieval list (1..kMaxListLength)
  double orientation_weight = 0.5;  // w: VCI's orientation term, per radian ("vci" only)
  int hmm_states = 8;               // HMM states, equal azimuth sectors (1..kMaxHmmStates)
  // S: the HMM decodes with emissions b_i^(2^S) (0: the thesis' HMM;
  // docs/design.md#orientation-hmm, "Sharpening").
  int hmm_sharpness = 0;
  // The accept / unknown rule (docs/design.md#accept-or-unknown): kTypicalDistance accepts when
  // T_M / mean Ttyp <= threshold; kCalibrated when the unknown statistic is at or below the
  // threshold a model-set calibration gives for false_accept_rate and known_accept_rate
  // (undecided without one: RecognitionEngine::SetCalibration).
  RejectionRule rejection = RejectionRule::kTypicalDistance;
  double threshold = 2.0;  // Th (finite, > 0)
  // kCalibrated's target share of unknown objects' windows accepted, in (0, 1), and the share of
  // the known objects' own windows it is raised to accept where look-alikes need more, in [0, 1)
  // (0: the target alone; docs/design.md#known-share). The product's engine takes its variant's
  // target instead (ProductFalseAcceptRate, core/engines/product_pipeline.h). Why these
  // defaults: docs/results/recognition.md, "Why 0.15 by default", and
  // docs/results/real-objects.md, "The known share".
  double false_accept_rate = 0.15;
  double known_accept_rate = 0.95;
  int top_k = 5;  // objects in each update's ranking (1..kMaxTopK)
  // lambda of the nearest-view blend, in [0, 1] (0: the engine's own score, as the thesis'
  // engines; docs/design.md#nearest-view-blend).
  double nearest_view_weight = 0;
  int averaged_views = 8;  // N_avg: active vision's averaged views (2..kMaxAveragedViews)
  // Active vision: objects scoring within this margin of the best are the ambiguous candidates
  // (finite, >= 0; docs/design.md#active-vision).
  double ambiguity_margin = 0.05;
  // Active vision: never suggest going back to a side the window has seen when the other side
  // is new (false: the thesis' rule alone).
  bool move_prefers_new_side = false;
  // The HMM on a catalogue of more than candidates_above objects scores only the objects the
  // view index proposes, candidate_objects per frame (0..kMaxCandidateObjects; 0: every object
  // at any size; docs/design.md#object-candidates).
  int candidate_objects = 0;
  int candidates_above = 0;  // 0..kMaxCandidatesAbove
};

// Throws std::invalid_argument naming the first option out of its range, as
// "<field_prefix><field> must be in <range>, got <value>", e.g. with the prefix "options.":
// "options.window must be in 1..64, got 65".
void ValidateEngineOptions(const EngineOptions& options,
                           std::string_view field_prefix = "engine option ");

// The nearest-view blend re-ranks at least this many objects: the runner-up the nearest view
// would promote is almost always among the engine's best four (docs/results/robustness.md).
inline constexpr int kNearestViewCandidates = 4;

// How many of its best objects an engine must rank exactly for an answer: top_k, and at least
// kNearestViewCandidates when the nearest-view blend re-ranks them.
int RankedDepth(const EngineOptions& options);

}  // namespace orbit
