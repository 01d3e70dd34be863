// Between what the engines answer (core/engines, core/decision) and the messages of
// proto/orbit/v1: decisions, moves, accept / unknown rules, a frame's update and an enrollment's
// report. The server writes them, the command line and the evaluation against a server read
// some back; a device reads the messages themselves and links none of this
// (docs/design.md#layers).
//
// Pure functions, thread-safe.
#pragma once

#include <optional>

#include "core/decision/enrollment_feedback.h"
#include "core/engines/recognition_engine.h"
#include "core/index/view_index.h"
#include "orbit/v1/models.pb.h"
#include "orbit/v1/recognition.pb.h"

namespace orbit {

v1::Decision ToProtoDecision(Decision decision);
// The inverse; DECISION_UNSPECIFIED and values this build does not know read as kUndecided (no
// answer).
Decision FromProtoDecision(v1::Decision decision);
v1::Move ToProtoMove(SuggestedMove move);
// Object ids are named from `index` (the name left empty for an id it does not hold).
v1::EnrollmentReport ToEnrollmentReport(const EnrollmentFeedback& feedback,
                                        const ViewIndexSnapshot& index);
v1::Rejection ToProtoRejection(RejectionRule rule);
// nullopt for REJECTION_UNSPECIFIED and values no rule has.
std::optional<RejectionRule> FromProtoRejection(v1::Rejection rule);

// An engine's update as the wire carries it, with each candidate's name from `index` (the
// snapshot the update was computed on).
v1::SessionUpdate ToSessionUpdate(const FrameUpdate& update, const ViewIndexSnapshot& index);

}  // namespace orbit
