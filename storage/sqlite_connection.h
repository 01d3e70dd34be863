// SqliteConnection: one open SQLite connection with its cache of prepared statements.
//
// Not thread-safe: a connection is used by one thread at a time (SqliteModelStore guards its
// writer with a mutex and hands each reading thread a connection of its own).
#pragma once

#include <chrono>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <unordered_map>

#include <sqlite3.h>

#include "storage/sqlite_statement.h"

namespace orbit {

// A prepared statement on loan from its connection's cache; reset (bindings cleared, read lock
// released) when the lease ends, so a finished SELECT never pins a WAL snapshot.
class StatementLease {
 public:
  explicit StatementLease(SqliteStatement& statement) : statement_(&statement) {}
  ~StatementLease() { statement_->Reset(); }
  StatementLease(const StatementLease&) = delete;
  StatementLease& operator=(const StatementLease&) = delete;

  SqliteStatement* operator->() const { return statement_; }
  SqliteStatement& operator*() const { return *statement_; }

 private:
  SqliteStatement* statement_;
};

class SqliteConnection {
 public:
  enum class Mode { kReadOnly, kReadWrite, kReadWriteCreate };

  // Opens `file`. Waits up to `busy_timeout` whenever another connection holds a lock it needs.
  // Throws StoreError kIo when the file cannot be opened. (A file that is not a database is only
  // noticed by the first statement, which throws kCorrupt.)
  SqliteConnection(const std::filesystem::path& file, Mode mode,
                   std::chrono::milliseconds busy_timeout);
  ~SqliteConnection();

  SqliteConnection(const SqliteConnection&) = delete;
  SqliteConnection& operator=(const SqliteConnection&) = delete;

  // Runs fixed SQL text (one or more statements without parameters: pragmas, schema changes).
  // Never pass text built from input: values go through Prepare and Bind.
  void Execute(std::string_view sql);

  // The cached statement for `sql`, prepared on first use. REQUIRES: the same statement is not
  // already on loan (no recursion over one statement).
  StatementLease Prepare(std::string_view sql);

  // The first column of the first row `sql` returns, as text ("" when there is no row).
  std::string QueryText(std::string_view sql);

  sqlite3* handle() const { return db_; }
  const std::filesystem::path& file() const { return file_; }

 private:
  std::filesystem::path file_;
  sqlite3* db_ = nullptr;
  // Destroyed (finalized) before db_ is closed: see the destructor.
  std::unordered_map<std::string, std::unique_ptr<SqliteStatement>> statements_;
};

}  // namespace orbit
