// The orientation HMM on a large catalogue (docs/design.md#object-candidates): on each frame the
// view index proposes the objects whose sector summaries are most like it
// (ViewIndexSnapshot::ObjectCandidates), and the HMM scores those, with the window's other
// candidates, instead of every object. Its per-frame cost then grows with the index's search,
// not with the catalogue.
//
// The answer is the HMM's (core/engines/orientation_hmm.h) on the objects it decodes: the same
// emissions to the last bit (core/engines/hmm_emissions.h), the same paths and scores. It differs
// only when an object that would rank was proposed in none of the window's frames: the
// candidates are approximate, and an object never proposed is never decoded.
//
// When the model set changes, the window keeps what its frames proposed: a removed object leaves
// them, an added one joins each frame that would have proposed it. A fresh session would search
// the index again for each frame and could also propose, in a removed object's place, an object
// just below a frame's last candidate; the kept window leaves that one out until a new frame
// proposes it. An enrollment then costs each open session the new object's emissions in its
// window, not a search per window frame.
//
// A session switches between the two engines as its catalogue crosses
// EngineOptions::candidates_above: up to that many objects it scores every object as the HMM
// always has; above, only candidates (candidate_objects per frame). The switch replays the window
// on the other engine, so every answer is the one a fresh session of that engine would give on the
// same window.
#pragma once

#include <memory>

#include "core/engines/recognition_engine.h"

namespace orbit {

// The HMM session described above: `every_object` (an HMM engine that scores every object, with
// the same options) answers while the catalogue holds at most options.candidates_above objects.
// Throws std::invalid_argument when options are out of range or candidate_objects is 0.
std::unique_ptr<RecognitionEngine> MakeCandidateHmmEngine(
    const EngineOptions& options, std::unique_ptr<RecognitionEngine> every_object);

}  // namespace orbit
