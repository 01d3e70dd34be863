// The model store an offline command works on: --db FILE (SQLite) or --store URL (PostgreSQL),
// exactly one of them, as `orbit serve` takes them.
#pragma once

#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "storage/model_store.h"

namespace orbit::cli {

struct StoreChoice {
  std::string db;     // a SQLite model store file
  std::string store;  // a libpq connection string
};

// Adds --db and --store to `command`; `db_help` describes --db for this command.
void AddStoreChoiceOptions(CLI::App& command, StoreChoice& choice, const std::string& db_help);

// Throws CLI::ValidationError for `command`, naming both flags, unless exactly one of `db` and
// `store` is given (orbit serve takes them into its configuration, the others into StoreChoice).
void RequireOneStore(const std::string& command, const std::string& db, const std::string& store);

// An open store and the name messages give it: the file, or the PostgreSQL target without its
// password.
struct ChosenStore {
  std::unique_ptr<ModelStore> store;
  std::string name;
};

// Opens the store `choice` names; a SQLite file is created when missing if `create_if_missing`.
// Throws CLI::ValidationError naming both flags when neither or both are given, and StoreError
// as the store's constructor.
ChosenStore OpenChosenStore(const std::string& command, const StoreChoice& choice,
                            bool create_if_missing);

}  // namespace orbit::cli
