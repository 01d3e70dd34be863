// An object as a server describes it (v1::ObjectInfo) in the model store's words
// (ObjectSummary), so `orbit list` and `orbit delete` print the same lines whether they read a
// local store (--db) or ask a server (--server).
#pragma once

#include "orbit/v1/types.pb.h"
#include "storage/model_store.h"

namespace orbit::cli {

// Throws std::invalid_argument for an unknown descriptor variant.
ObjectSummary SummaryOf(const v1::ObjectInfo& info);

}  // namespace orbit::cli
