#include "storage/sqlite_transaction.h"

#include "storage/store_error.h"

namespace orbit {

SqliteTransaction::SqliteTransaction(SqliteConnection& connection, Mode mode)
    : connection_(connection) {
  try {
    connection_.Prepare(mode == Mode::kWrite ? "BEGIN IMMEDIATE" : "BEGIN DEFERRED")->Run();
  } catch (const StoreError& e) {
    if (e.code() != StoreError::Code::kBusy) throw;
    throw StoreError(StoreError::Code::kBusy,
                     connection_.file().string() +
                         " is locked by another writer for longer than the busy timeout (" +
                         e.what() + ")");
  }
}

SqliteTransaction::~SqliteTransaction() {
  // After some errors (SQLITE_FULL, SQLITE_IOERR, ...) SQLite has already rolled back on its own.
  if (!open_ || sqlite3_get_autocommit(connection_.handle()) != 0) return;
  try {
    connection_.Prepare("ROLLBACK")->Run();
  } catch (...) {
    // Nothing more to do: SQLite rolls back what the failed ROLLBACK left when the connection
    // closes, and a hot journal / WAL is never applied without its commit record.
  }
}

void SqliteTransaction::Commit() {
  connection_.Prepare("COMMIT")->Run();
  open_ = false;
}

}  // namespace orbit
