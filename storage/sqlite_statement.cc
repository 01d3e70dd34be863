#include "storage/sqlite_statement.h"

#include <string>

#include "storage/sqlite_error.h"

namespace orbit {
namespace {

std::string Context(sqlite3_stmt* statement) {
  const char* sql = statement != nullptr ? sqlite3_sql(statement) : nullptr;
  return std::string("SQL statement `") + (sql != nullptr ? sql : "?") + "` failed";
}

}  // namespace

SqliteStatement::SqliteStatement(sqlite3* db, std::string_view sql) : db_(db) {
  const int rc = sqlite3_prepare_v3(db, sql.data(), static_cast<int>(sql.size()),
                                    SQLITE_PREPARE_PERSISTENT, &statement_, nullptr);
  if (rc != SQLITE_OK) {
    throw SqliteError(rc, db, "cannot prepare `" + std::string(sql) + "`");
  }
}

SqliteStatement::~SqliteStatement() { sqlite3_finalize(statement_); }

void SqliteStatement::Bind(int index, std::int64_t value) {
  const int rc = sqlite3_bind_int64(statement_, index, value);
  if (rc != SQLITE_OK) throw SqliteError(rc, db_, Context(statement_));
}

void SqliteStatement::Bind(int index, double value) {
  const int rc = sqlite3_bind_double(statement_, index, value);
  if (rc != SQLITE_OK) throw SqliteError(rc, db_, Context(statement_));
}

void SqliteStatement::Bind(int index, std::string_view text) {
  const int rc = sqlite3_bind_text64(statement_, index, text.data(), text.size(), SQLITE_TRANSIENT,
                                     SQLITE_UTF8);
  if (rc != SQLITE_OK) throw SqliteError(rc, db_, Context(statement_));
}

void SqliteStatement::BindBlob(int index, std::span<const std::uint8_t> bytes) {
  // A zero-length blob still binds as a blob (not NULL): sqlite3_bind_blob64 with a null pointer
  // would bind NULL.
  static const std::uint8_t kNothing = 0;
  const int rc = sqlite3_bind_blob64(statement_, index, bytes.empty() ? &kNothing : bytes.data(),
                                     bytes.size(), SQLITE_TRANSIENT);
  if (rc != SQLITE_OK) throw SqliteError(rc, db_, Context(statement_));
}

void SqliteStatement::BindNull(int index) {
  const int rc = sqlite3_bind_null(statement_, index);
  if (rc != SQLITE_OK) throw SqliteError(rc, db_, Context(statement_));
}

bool SqliteStatement::Step() {
  const int rc = sqlite3_step(statement_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) return false;
  throw SqliteError(rc, db_, Context(statement_));
}

void SqliteStatement::Run() {
  while (Step()) {
  }
}

bool SqliteStatement::IsNull(int column) const {
  return sqlite3_column_type(statement_, column) == SQLITE_NULL;
}

std::int64_t SqliteStatement::ColumnInt64(int column) const {
  return sqlite3_column_int64(statement_, column);
}

double SqliteStatement::ColumnDouble(int column) const {
  return sqlite3_column_double(statement_, column);
}

std::string_view SqliteStatement::ColumnText(int column) const {
  const auto* text = reinterpret_cast<const char*>(sqlite3_column_text(statement_, column));
  const int size = sqlite3_column_bytes(statement_, column);
  return text != nullptr ? std::string_view(text, static_cast<std::size_t>(size))
                         : std::string_view();
}

std::span<const std::uint8_t> SqliteStatement::ColumnBlob(int column) const {
  const auto* bytes = static_cast<const std::uint8_t*>(sqlite3_column_blob(statement_, column));
  const int size = sqlite3_column_bytes(statement_, column);
  return bytes != nullptr ? std::span<const std::uint8_t>(bytes, static_cast<std::size_t>(size))
                          : std::span<const std::uint8_t>();
}

void SqliteStatement::Reset() {
  sqlite3_reset(statement_);
  sqlite3_clear_bindings(statement_);
}

}  // namespace orbit
