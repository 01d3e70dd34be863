#include "server/audit_log.h"

#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <iostream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "api/status_code_name.h"

namespace orbit::server {
namespace {

// UTC, to the millisecond: 2026-11-27T07:50:01.123Z.
std::string Now() {
  const auto now = std::chrono::system_clock::now();
  const std::time_t seconds = std::chrono::system_clock::to_time_t(now);
  const auto millis =
      std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S", &utc);
  char full[40];
  std::snprintf(full, sizeof full, "%s.%03dZ", text, static_cast<int>(millis));
  return full;
}

}  // namespace

AuditLog::AuditLog(const std::string& destination) {
  if (destination == "-") {
    to_stderr_ = true;
    return;
  }
  // Created readable by the server alone: the log names tokens and peers.
  const int fd = ::open(destination.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0600);
  if (fd < 0) throw std::runtime_error("cannot open the audit log " + destination);
  ::close(fd);
  MutexLock lock(&mutex_);
  file_.open(destination, std::ios::app);
  if (!file_) throw std::runtime_error("cannot open the audit log " + destination);
}

void AuditLog::Record(const AuditEvent& event) {
  nlohmann::json line = {
      {"time", Now()},      {"call", event.call},     {"token", event.token},
      {"peer", event.peer}, {"object", event.object}, {"outcome", StatusCodeName(event.outcome)},
  };
  if (!event.message.empty()) line["message"] = event.message;
  // Replaces invalid UTF-8 (an object name is checked, but a refusal's message may quote input).
  const std::string text = line.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  MutexLock lock(&mutex_);
  if (to_stderr_) {
    std::cerr << text << std::endl;
  } else {
    file_ << text << std::endl;
  }
}

}  // namespace orbit::server
