#include "storage/model_change.h"

#include <cstdio>
#include <ctime>
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

std::optional<std::chrono::system_clock::time_point> CommittedTime(const ModelChange& change) {
  std::tm time{};
  int millisecond = 0;
  char zone = 0;
  int consumed = 0;
  if (std::sscanf(change.committed_at.c_str(), "%4d-%2d-%2dT%2d:%2d:%2d.%3d%c%n", &time.tm_year,
                  &time.tm_mon, &time.tm_mday, &time.tm_hour, &time.tm_min, &time.tm_sec,
                  &millisecond, &zone, &consumed) != 8 ||
      zone != 'Z' || consumed != static_cast<int>(change.committed_at.size())) {
    return std::nullopt;
  }
  time.tm_year -= 1900;
  time.tm_mon -= 1;
  const std::time_t seconds = ::timegm(&time);
  return std::chrono::system_clock::from_time_t(seconds) + std::chrono::milliseconds(millisecond);
}

}  // namespace orbit
