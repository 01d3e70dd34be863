#include "storage/sqlite_connection.h"

#include "storage/sqlite_error.h"

namespace orbit {

SqliteConnection::SqliteConnection(const std::filesystem::path& file, Mode mode,
                                   std::chrono::milliseconds busy_timeout)
    : file_(file) {
  int flags = SQLITE_OPEN_NOMUTEX | SQLITE_OPEN_EXRESCODE;
  switch (mode) {
    case Mode::kReadOnly: flags |= SQLITE_OPEN_READONLY; break;
    case Mode::kReadWrite: flags |= SQLITE_OPEN_READWRITE; break;
    case Mode::kReadWriteCreate: flags |= SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE; break;
  }
  const int rc = sqlite3_open_v2(file.c_str(), &db_, flags, nullptr);
  if (rc != SQLITE_OK) {
    StoreError error = SqliteError(rc, db_, "cannot open " + file.string());
    sqlite3_close_v2(db_);
    throw error;
  }
  sqlite3_busy_timeout(db_, static_cast<int>(busy_timeout.count()));
}

SqliteConnection::~SqliteConnection() {
  statements_.clear();
  sqlite3_close_v2(db_);
}

void SqliteConnection::Execute(std::string_view sql) {
  char* message = nullptr;
  const std::string text(sql);
  const int rc = sqlite3_exec(db_, text.c_str(), nullptr, nullptr, &message);
  sqlite3_free(message);  // the same text as sqlite3_errmsg, which SqliteError reads
  if (rc != SQLITE_OK) throw SqliteError(rc, db_, "`" + text + "` on " + file_.string());
}

StatementLease SqliteConnection::Prepare(std::string_view sql) {
  auto found = statements_.find(std::string(sql));
  if (found == statements_.end()) {
    found =
        statements_.emplace(std::string(sql), std::make_unique<SqliteStatement>(db_, sql)).first;
  }
  return StatementLease(*found->second);
}

std::string SqliteConnection::QueryText(std::string_view sql) {
  StatementLease statement = Prepare(sql);
  return statement->Step() ? std::string(statement->ColumnText(0)) : std::string();
}

}  // namespace orbit
