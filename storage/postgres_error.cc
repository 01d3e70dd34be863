#include "storage/postgres_error.h"

#include <string>

namespace orbit {
namespace {

StoreError::Code CodeOf(std::string_view sqlstate) {
  using Code = StoreError::Code;
  if (sqlstate.size() != 5) return Code::kIo;  // no answer from the server: the link is down
  if (sqlstate == "23505") return Code::kAlreadyExists;  // unique_violation
  if (sqlstate == "53100") return Code::kFull;           // disk_full
  if (sqlstate == "55P03" || sqlstate == "40001" || sqlstate == "40P01" || sqlstate == "53300" ||
      sqlstate == "57P03") {
    // lock_not_available (lock_timeout), serialization_failure, deadlock_detected,
    // too_many_connections, cannot_connect_now (starting up or shutting down)
    return Code::kBusy;
  }
  if (sqlstate == "XX001" || sqlstate == "XX002") return Code::kCorrupt;  // data / index corrupted
  const std::string_view group = sqlstate.substr(0, 2);
  if (group == "23" || group == "22") return Code::kConstraint;  // integrity, data exceptions
  if (group == "08" || group == "58" || group == "57")
    return Code::kIo;  // connection, system,
                       // operator intervention
  return Code::kInternal;
}

}  // namespace

StoreError PostgresError(std::string_view sqlstate, std::string_view message,
                         std::string_view context) {
  std::string text(message);
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return StoreError(CodeOf(sqlstate), std::string(context) + ": " + text);
}

}  // namespace orbit
