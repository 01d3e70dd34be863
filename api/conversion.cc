#include "api/conversion.h"

#include <cstdint>
#include <span>
#include <stdexcept>

namespace orbit {

v1::DescriptorVariant ToProtoVariant(DescriptorVariant variant) {
  switch (variant) {
    case DescriptorVariant::kCeddLire: return v1::CEDD_LIRE;
    case DescriptorVariant::kCeddFull: return v1::CEDD_FULL;
    case DescriptorVariant::kCeddRobust: return v1::CEDD_ROBUST;
    case DescriptorVariant::kCeddHsvHog: return v1::CEDD_HSV_HOG;
  }
  return v1::DESCRIPTOR_VARIANT_UNSPECIFIED;
}

DescriptorVariant FromProtoVariant(v1::DescriptorVariant variant) {
  switch (variant) {
    case v1::CEDD_LIRE: return DescriptorVariant::kCeddLire;
    case v1::CEDD_FULL: return DescriptorVariant::kCeddFull;
    case v1::CEDD_ROBUST: return DescriptorVariant::kCeddRobust;
    case v1::CEDD_HSV_HOG: return DescriptorVariant::kCeddHsvHog;
    default: throw std::invalid_argument("descriptor variant is " + ProtoVariantName(variant));
  }
}

std::string ProtoVariantName(v1::DescriptorVariant variant) {
  switch (variant) {
    case v1::CEDD_LIRE:
    case v1::CEDD_FULL:
    case v1::CEDD_ROBUST:
    case v1::CEDD_HSV_HOG: return std::string(VariantName(FromProtoVariant(variant)));
    case v1::DESCRIPTOR_VARIANT_UNSPECIFIED: return "unspecified";
    default: return "unknown (" + std::to_string(variant) + ")";
  }
}

DescriptorValues DescriptorFromWire(const std::string& cedd, const std::string& appearance,
                                    DescriptorVariant variant, std::string_view message) {
  const auto bytes = [](const std::string& text) {
    return std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(text.data()),
                                         text.size());
  };
  const std::string prefix(message);
  DescriptorValues values =
      DescriptorFromBytes(bytes(cedd), DescriptorVariant::kCeddFull, prefix + ".cedd");
  const std::size_t expected = static_cast<std::size_t>(DescriptorLength(variant) - kCeddSize);
  if (appearance.size() != expected) {
    throw std::invalid_argument(prefix + ".appearance has " + std::to_string(appearance.size()) +
                                " values, expected " + std::to_string(expected) + " for " +
                                std::string(VariantName(variant)));
  }
  ValidateDescriptorValues(bytes(appearance), prefix + ".appearance");
  std::copy(appearance.begin(), appearance.end(), values.begin() + kCeddSize);
  return values;
}

void SetWireDescriptor(const DescriptorValues& values, DescriptorVariant variant, std::string* cedd,
                       std::string* appearance) {
  const std::span<const std::uint8_t> all = DescriptorBytes(values, variant);
  cedd->assign(all.begin(), all.begin() + kCeddSize);
  appearance->assign(all.begin() + kCeddSize, all.end());
}

v1::View ToProtoView(const ModelView& view, DescriptorVariant variant,
                     const std::string& thumbnail) {
  v1::View out;
  SetWireDescriptor(view.descriptor, variant, out.mutable_cedd(), out.mutable_appearance());
  out.set_azimuth_deg(view.azimuth);
  if (view.elevation) out.set_elevation_deg(*view.elevation);
  out.set_typical_distance(view.typical_distance);
  if (!thumbnail.empty()) out.set_thumbnail(thumbnail);
  return out;
}

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
