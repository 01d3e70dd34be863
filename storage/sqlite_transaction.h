// SqliteTransaction: a transaction that rolls back unless committed, so an exception anywhere in
// a write leaves the database as it was (ModelStore: "a method that throws has changed nothing").
#pragma once

#include "storage/sqlite_connection.h"

namespace orbit {

class SqliteTransaction {
 public:
  enum class Mode {
    // BEGIN DEFERRED: the snapshot is taken by the first read; every read of the transaction
    // sees that one snapshot, whatever commits meanwhile (WAL).
    kRead,
    // BEGIN IMMEDIATE: takes the write lock at once (waiting up to the busy timeout), so a write
    // never fails half-way because another writer got in first.
    kWrite,
  };

  // Begins the transaction. Throws StoreError (kBusy when the write lock is not free in time).
  SqliteTransaction(SqliteConnection& connection, Mode mode);
  // Rolls back unless Commit succeeded. Never throws.
  ~SqliteTransaction();

  SqliteTransaction(const SqliteTransaction&) = delete;
  SqliteTransaction& operator=(const SqliteTransaction&) = delete;

  // Commits; for a write, durable on return (synchronous=FULL). Throws StoreError, and then the
  // destructor rolls back.
  void Commit();

 private:
  SqliteConnection& connection_;
  bool open_ = true;
};

}  // namespace orbit
