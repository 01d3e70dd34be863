#include "storage/postgres_change_listener.h"

#include <poll.h>

#include <cerrno>

#include "storage/postgres_connection.h"
#include "storage/postgres_model_store.h"
#include "storage/store_error.h"

namespace orbit {

PostgresChangeListener::PostgresChangeListener(const std::string& conninfo)
    : connection_(std::make_unique<PostgresConnection>(conninfo, /*lock_timeout_ms=*/0)) {
  connection_->Execute(std::string("LISTEN ") + kModelChangesChannel);
}

PostgresChangeListener::~PostgresChangeListener() = default;

bool PostgresChangeListener::Wait(std::chrono::milliseconds timeout) {
  // Notifications that arrived with an earlier reply are already buffered: no need to wait.
  if (!connection_->TakeNotifications().empty()) return true;
  pollfd socket{.fd = connection_->Socket(), .events = POLLIN, .revents = 0};
  const int ready = ::poll(&socket, 1, static_cast<int>(timeout.count()));
  if (ready < 0 && errno != EINTR) {
    throw StoreError(StoreError::Code::kIo,
                     "cannot wait on the connection to PostgreSQL " + connection_->target());
  }
  if (ready <= 0) return false;
  return !connection_->TakeNotifications().empty();
}

}  // namespace orbit
