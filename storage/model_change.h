// ModelChange: one committed write of a shared model store, as its change log records it
// (storage/postgres_model_store.h: the table model_changes). Replicas of the server follow the
// log to learn what other replicas wrote.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "core/model/object_model.h"

namespace orbit {

enum class ModelChangeKind { kEnroll, kAddViews, kDelete, kRename };

// The kind's name in the change log: "enroll", "add_views", "delete" or "rename".
std::string_view ModelChangeKindName(ModelChangeKind kind);

// Inverse of ModelChangeKindName; nullopt for any other text.
std::optional<ModelChangeKind> ParseModelChangeKind(std::string_view name);

struct ModelChange {
  std::int64_t seq = 0;  // increases with each write, in commit order; never reused
  ObjectId object_id = 0;
  ModelChangeKind kind = ModelChangeKind::kEnroll;
  // When the write recorded it, just before its commit: UTC, ISO 8601 with milliseconds, as
  // ObjectSummary's times. For people; followers go by seq.
  std::string committed_at;

  bool operator==(const ModelChange&) const = default;
};

// Thrown when the changes after `after_seq` were asked for but the log no longer holds all of
// them: it was pruned through `pruned_through` (docs/design.md#change-log). Whoever asked cannot
// follow the log from there, and must read every object again instead.
class ChangeLogPruned : public std::runtime_error {
 public:
  ChangeLogPruned(std::int64_t after_seq, std::int64_t pruned_through)
      : std::runtime_error("the change log was pruned past change " + std::to_string(after_seq) +
                           " (through " + std::to_string(pruned_through) + ")"),
        after_seq_(after_seq),
        pruned_through_(pruned_through) {}

  std::int64_t after_seq() const { return after_seq_; }
  std::int64_t pruned_through() const { return pruned_through_; }

 private:
  std::int64_t after_seq_;
  std::int64_t pruned_through_;
};

// `committed_at` as a time point; nullopt when it is not "YYYY-MM-DDTHH:MM:SS.mmmZ".
std::optional<std::chrono::system_clock::time_point> CommittedTime(const ModelChange& change);

}  // namespace orbit
