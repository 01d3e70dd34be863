#include "storage/model_change.h"

#include <utility>

namespace orbit {
namespace {

constexpr std::array<std::pair<ModelChangeKind, std::string_view>, 4> kKindNames = {{
    {ModelChangeKind::kEnroll, "enroll"},
    {ModelChangeKind::kAddViews, "add_views"},
    {ModelChangeKind::kDelete, "delete"},
    {ModelChangeKind::kRename, "rename"},
}};

}  // namespace

std::string_view ModelChangeKindName(ModelChangeKind kind) {
  for (const auto& [k, name] : kKindNames) {
    if (k == kind) return name;
  }
  return "?";
}

std::optional<ModelChangeKind> ParseModelChangeKind(std::string_view name) {
  for (const auto& [kind, n] : kKindNames) {
    if (n == name) return kind;
  }
  return std::nullopt;
}

}  // namespace orbit
