// What the storage tests share: synthetic object models (scratch folders: test_data.h), the
// StoreError a call throws, a raw SQLite connection to look at a store's file from outside
// the store, and the process's umask and a file's mode.
#pragma once

#include <cstdint>
#include <filesystem>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <sqlite3.h>
#include <sys/stat.h>

#include "core/model/object_model.h"
#include "storage/model_store.h"
#include "storage/store_error.h"
#include "tests/support/test_data.h"

namespace orbit::testing {

// A view whose descriptor values (all in 0..7) are a deterministic function of `seed`, distinct
// for distinct seeds in practice: 144 draws of std::mt19937 (its output is fixed by the standard).
inline ModelView SyntheticView(int seed, double azimuth) {
  ModelView view;
  std::mt19937 random(static_cast<std::uint32_t>(seed));
  for (int i = 0; i < kCeddSize; ++i) view.descriptor[i] = static_cast<std::uint8_t>(random() % 8);
  view.azimuth = azimuth;
  view.typical_distance = 0.01 * (seed % 50);
  return view;
}

// An object of `view_count` views at equal azimuth steps, view f with seed `seed + f`.
inline Enrollment SyntheticObject(const std::string& name, int view_count, int seed = 1) {
  Enrollment enrollment;
  enrollment.name = name;
  for (int f = 0; f < view_count; ++f) {
    enrollment.views.push_back(SyntheticView(seed + f, 360.0 * f / view_count));
  }
  return enrollment;
}

// The StoreError code and message `call` throws; fails the test when it throws none.
template <typename Call>
std::pair<StoreError::Code, std::string> StoreErrorOf(Call call) {
  try {
    call();
  } catch (const StoreError& e) {
    return {e.code(), e.what()};
  }
  ADD_FAILURE() << "no StoreError thrown";
  return {StoreError::Code::kInternal, ""};
}

// A plain SQLite connection to a store's file, bypassing the store: to count rows, check
// integrity, or hold locks the way another process would.
class RawDatabase {
 public:
  explicit RawDatabase(const std::filesystem::path& file) {
    if (sqlite3_open(file.c_str(), &db_) != SQLITE_OK) {
      throw std::runtime_error("cannot open " + file.string() + ": " + sqlite3_errmsg(db_));
    }
    sqlite3_busy_timeout(db_, 10000);
  }
  ~RawDatabase() { sqlite3_close(db_); }
  RawDatabase(const RawDatabase&) = delete;
  RawDatabase& operator=(const RawDatabase&) = delete;

  void Execute(const std::string& sql) {
    char* message = nullptr;
    if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &message) != SQLITE_OK) {
      const std::string text = message != nullptr ? message : "?";
      sqlite3_free(message);
      throw std::runtime_error("`" + sql + "` failed: " + text);
    }
  }

  // The first column of every row of `sql`, as text (NULL as "NULL").
  std::vector<std::string> Column(const std::string& sql) {
    sqlite3_stmt* statement = nullptr;
    if (sqlite3_prepare_v2(db_, sql.c_str(), -1, &statement, nullptr) != SQLITE_OK) {
      throw std::runtime_error("cannot prepare `" + sql + "`: " + sqlite3_errmsg(db_));
    }
    std::vector<std::string> values;
    int rc = 0;
    while ((rc = sqlite3_step(statement)) == SQLITE_ROW) {
      const auto* text = reinterpret_cast<const char*>(sqlite3_column_text(statement, 0));
      values.push_back(text != nullptr ? text : "NULL");
    }
    sqlite3_finalize(statement);
    if (rc != SQLITE_DONE) throw std::runtime_error("`" + sql + "` failed: " + sqlite3_errmsg(db_));
    return values;
  }

  // The single value of `sql`.
  std::string Text(const std::string& sql) {
    const std::vector<std::string> values = Column(sql);
    if (values.size() != 1) throw std::runtime_error("`" + sql + "` gave no single value");
    return values[0];
  }
  std::int64_t Int(const std::string& sql) { return std::stoll(Text(sql)); }

 private:
  sqlite3* db_ = nullptr;
};

// Sets the process's umask for the span of a test (the umask a user's shell typically has is
// 022: files readable by everyone), then restores it.
class ScopedUmask {
 public:
  explicit ScopedUmask(mode_t mask) : previous_(::umask(mask)) {}
  ~ScopedUmask() { ::umask(previous_); }
  ScopedUmask(const ScopedUmask&) = delete;
  ScopedUmask& operator=(const ScopedUmask&) = delete;

 private:
  mode_t previous_;
};

// The permission bits of `file`, as `ls -l` shows them in octal (0600, 0644).
inline unsigned FileMode(const std::filesystem::path& file) {
  return static_cast<unsigned>(std::filesystem::status(file).permissions() &
                               std::filesystem::perms::mask);
}

}  // namespace orbit::testing
