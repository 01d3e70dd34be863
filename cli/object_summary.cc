#include "cli/object_summary.h"

#include "client/models_client.h"

namespace orbit::cli {

ObjectSummary SummaryOf(const v1::ObjectInfo& info) {
  ObjectSummary summary;
  summary.id = info.id();
  summary.name = info.name();
  summary.variant = FromProtoVariant(info.variant());
  summary.view_count = info.view_count();
  summary.created_at = info.created_at();
  summary.updated_at = info.updated_at();
  summary.metadata = info.metadata_json().empty() ? "{}" : info.metadata_json();
  return summary;
}

}  // namespace orbit::cli
