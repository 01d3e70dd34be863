// SqliteStatement: one prepared SQL statement, kept and reused (SqliteConnection caches them), so
// that SQL text is compiled once and values always travel as bound parameters, never spliced into
// the text.
//
// Not thread-safe: used by one thread at a time, like its connection.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include <sqlite3.h>

namespace orbit {

class SqliteStatement {
 public:
  // Prepares `sql` (one statement) on `db` for repeated use. Throws StoreError on a bad statement.
  SqliteStatement(sqlite3* db, std::string_view sql);
  ~SqliteStatement();

  SqliteStatement(const SqliteStatement&) = delete;
  SqliteStatement& operator=(const SqliteStatement&) = delete;

  // Bind parameter `index` (1-based, as in `?1`). The text and blob overloads copy the bytes.
  void Bind(int index, std::int64_t value);
  void Bind(int index, double value);
  void Bind(int index, std::string_view text);
  void BindBlob(int index, std::span<const std::uint8_t> bytes);
  void BindNull(int index);

  // Runs the statement to its next row: true when a row is ready for the Column* calls, false when
  // it is done. Throws StoreError on failure.
  bool Step();
  // Runs a statement that returns no rows.
  void Run();

  // Columns of the current row (0-based). Text and blobs stay valid until the next Step or Reset.
  bool IsNull(int column) const;
  std::int64_t ColumnInt64(int column) const;
  double ColumnDouble(int column) const;
  std::string_view ColumnText(int column) const;
  std::span<const std::uint8_t> ColumnBlob(int column) const;

  // Ends the current run and clears the bindings, ready for reuse. Never throws: a failure of the
  // run was already reported by Step.
  void Reset();

 private:
  sqlite3* db_;
  sqlite3_stmt* statement_ = nullptr;
};

}  // namespace orbit
