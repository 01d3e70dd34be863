#include "api/engines/conversion.h"

namespace orbit {

v1::Decision ToProtoDecision(Decision decision) {
  switch (decision) {
    case Decision::kAccept: return v1::DECISION_ACCEPT;
    case Decision::kUnknown: return v1::DECISION_UNKNOWN;
    case Decision::kUndecided: return v1::DECISION_UNDECIDED;
  }
  return v1::DECISION_UNSPECIFIED;
}

Decision FromProtoDecision(v1::Decision decision) {
  switch (decision) {
    case v1::DECISION_ACCEPT: return Decision::kAccept;
    case v1::DECISION_UNKNOWN: return Decision::kUnknown;
    default: return Decision::kUndecided;
  }
}

v1::EnrollmentReport ToEnrollmentReport(const EnrollmentFeedback& feedback,
                                        const ViewIndexSnapshot& index) {
  v1::EnrollmentReport report;
  for (const AzimuthGap& gap : feedback.gaps) {
    v1::AzimuthGap* out = report.add_gaps();
    out->set_from_deg(gap.from);
    out->set_to_deg(gap.to);
  }
  for (const double azimuth : feedback.redundant_azimuths)
    report.add_redundant_azimuths_deg(azimuth);
  for (const Confusion& confusion : feedback.confusable) {
    v1::ConfusableObject* out = report.add_confusable();
    out->set_id(confusion.object);
    if (const IndexedObject* object = index.Find(confusion.object))
      out->set_name(object->model().name);
    out->set_similarity(confusion.similarity);
    out->set_closer_views(confusion.closer_views);
  }
  return report;
}

v1::Rejection ToProtoRejection(RejectionRule rule) {
  return rule == RejectionRule::kCalibrated ? v1::REJECTION_CALIBRATED : v1::REJECTION_TH;
}

std::optional<RejectionRule> FromProtoRejection(v1::Rejection rule) {
  switch (rule) {
    case v1::REJECTION_TH: return RejectionRule::kTypicalDistance;
    case v1::REJECTION_CALIBRATED: return RejectionRule::kCalibrated;
    default: return std::nullopt;
  }
}

v1::Move ToProtoMove(SuggestedMove move) {
  switch (move) {
    case SuggestedMove::kNone: return v1::MOVE_NONE;
    case SuggestedMove::kLeft: return v1::MOVE_LEFT;
    case SuggestedMove::kRight: return v1::MOVE_RIGHT;
  }
  return v1::MOVE_UNSPECIFIED;
}

v1::SessionUpdate ToSessionUpdate(const FrameUpdate& update, const ViewIndexSnapshot& index) {
  v1::SessionUpdate out;
  out.set_frame_index(update.frame_index);
  for (const RankedObject& ranked : update.ranking) {
    v1::Candidate* candidate = out.add_candidates();
    candidate->set_id(ranked.object);
    candidate->set_score(ranked.score);
    if (const IndexedObject* object = index.Find(ranked.object)) {
      candidate->set_name(object->model().name);
    }
  }
  out.set_decision(ToProtoDecision(update.decision));
  out.set_move(ToProtoMove(update.move));
  out.set_confidence(update.confidence);
  if (update.pose) {
    out.mutable_pose()->set_azimuth_deg(update.pose->azimuth);
    out.mutable_pose()->set_spread_deg(update.pose->spread);
  }
  return out;
}

}  // namespace orbit
