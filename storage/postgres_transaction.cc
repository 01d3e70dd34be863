#include "storage/postgres_transaction.h"

#include <string>

#include "storage/store_error.h"

namespace orbit {

PostgresTransaction::PostgresTransaction(PostgresConnection& connection, Mode mode)
    : connection_(connection) {
  if (mode == Mode::kSnapshot) {
    connection_.Execute("BEGIN ISOLATION LEVEL REPEATABLE READ READ ONLY");
    return;
  }
  connection_.Execute("BEGIN ISOLATION LEVEL READ COMMITTED");
  try {
    connection_.Execute("SELECT pg_advisory_xact_lock(" + std::to_string(kPostgresWriteLockKey) +
                        ")");
  } catch (const StoreError& e) {
    if (e.code() != StoreError::Code::kBusy) throw;
    throw StoreError(StoreError::Code::kBusy,
                     "PostgreSQL " + connection_.target() +
                         ": another writer held the model store for longer than the busy "
                         "timeout (" +
                         e.what() + ")");
  }
}

PostgresTransaction::~PostgresTransaction() {
  if (!open_ || !connection_.InTransaction()) return;
  try {
    connection_.Execute("ROLLBACK");
  } catch (...) {
    // The connection is broken: the server rolls back what it had when the session ends.
  }
}

void PostgresTransaction::Commit() {
  try {
    connection_.Execute("COMMIT");
  } catch (const StoreError& e) {
    if (!connection_.Lost()) throw;
    open_ = false;
    throw StoreError(e.code(), std::string(e.what()) +
                                   " (during COMMIT: whether the change was stored is unknown)");
  }
  open_ = false;
}

}  // namespace orbit
