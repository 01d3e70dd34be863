// PostgresTransaction: a transaction that rolls back unless committed, so an exception anywhere
// in a write leaves the database as it was (ModelStore: "a method that throws has changed
// nothing").
#pragma once

#include "storage/postgres_connection.h"

namespace orbit {

class PostgresTransaction {
 public:
  enum class Mode {
    // REPEATABLE READ, READ ONLY: every statement sees the one snapshot taken by the first.
    kSnapshot,
    // READ COMMITTED, then the store's write lock (a transaction-scoped advisory lock, waited for
    // up to the connection's lock_timeout): one writer at a time across every process using the
    // database, and each statement sees everything committed before it.
    kWrite,
  };

  // Begins the transaction. Throws StoreError (kBusy when the write lock is not free in time).
  PostgresTransaction(PostgresConnection& connection, Mode mode);
  // Rolls back unless Commit succeeded. Never throws.
  ~PostgresTransaction();

  PostgresTransaction(const PostgresTransaction&) = delete;
  PostgresTransaction& operator=(const PostgresTransaction&) = delete;

  // Commits; durable on return (synchronous_commit as the server is configured: on by default).
  // Throws StoreError; when the connection is lost during the commit the outcome is unknown
  // (the message says so), otherwise the transaction is rolled back.
  void Commit();

 private:
  PostgresConnection& connection_;
  bool open_ = true;
};

// The key of the store's write lock (pg_advisory_xact_lock): "orbit" in ASCII. Every write and
// every schema migration holds it, so writes are serialised and the change log's sequence
// numbers are in commit order.
inline constexpr long long kPostgresWriteLockKey = 0x6f72626974;

}  // namespace orbit
