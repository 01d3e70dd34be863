// Active vision (docs/design.md#active-vision): where should the device move so that the objects
// still in contention look most different from one another?
//
// Each object has N_avg averaged views (IndexedObject::Sectors(N_avg): the mean CEDD of the views
// in each equal azimuth sector). For every ambiguous candidate, its estimated orientation (the
// model azimuth facing the camera now) picks the averaged view one sector to the right
// (azimuth + 360/N_avg: what the camera would see after moving RIGHT, toward increasing device
// azimuth) and one sector to the left. A side's separation is the smallest Tanimoto distance
// between any two candidates' averaged views on that side: the pair most likely to stay confused
// decides, which is the intent of the thesis' eq. 5.10 (minimise ambiguity) rather than its
// literal distance sum, which one very different candidate can dominate. Ties are broken by the
// sum of pairwise distances; a complete tie gives NONE.
//
// Pure and thread-safe.
#pragma once

#include <span>
#include <string_view>

#include "core/index/indexed_object.h"

namespace orbit {

// Where the device should move next to settle an ambiguity. RIGHT means toward increasing
// device azimuth, LEFT toward decreasing.
enum class SuggestedMove { kNone, kLeft, kRight };

std::string_view MoveName(SuggestedMove move);  // "LEFT", "RIGHT", "NONE"

struct MoveCandidate {
  const IndexedObject* object = nullptr;
  double azimuth = 0;  // estimated model azimuth facing the camera at the latest frame (degrees)
};

// NONE for fewer than two candidates (one dominates); else LEFT or RIGHT by the rule above,
// except that a side the device has already seen is not suggested when the other is new.
// `seen_turns` are the window's earlier frames' measured turns from the latest frame (degrees,
// positive to the right; MeasuredTurn(latest, frame)): a side is seen when a frame lies on it
// less than one and a half sectors (of 360 / averaged_views) away. Going back shows what the window
// already holds, so the new side is the better bet whatever the averaged views say: on COIL-100
// under motion blur, four views following the separation rule alone are less often right than four
// views stepping one way (docs/results/recognition.md, "Active vision: does following the move
// suggestion help?"). Empty `seen_turns`: the separation rule alone, as the thesis' methods use it.
// Throws std::invalid_argument when averaged_views < 2 or a candidate's object is null.
SuggestedMove SuggestMove(std::span<const MoveCandidate> candidates, int averaged_views,
                          std::span<const double> seen_turns = {});

// The separation of one side, as defined above: {smallest pairwise distance, sum of pairwise
// distances} between the candidates' averaged views at azimuth + offset. Exposed for tests.
struct Separation {
  double smallest = 0;
  double sum = 0;
};
Separation SideSeparation(std::span<const MoveCandidate> candidates, int averaged_views,
                          double offset);

}  // namespace orbit
