#include "cli/store_choice.h"

#include "storage/postgres_connection.h"
#include "storage/postgres_model_store.h"
#include "storage/sqlite_model_store.h"

namespace orbit::cli {

void AddStoreChoiceOptions(CLI::App& command, StoreChoice& choice, const std::string& db_help) {
  command.add_option("--db", choice.db, db_help);
  command.add_option("--store", choice.store,
                     "a PostgreSQL model store instead of --db: a libpq connection string,\n"
                     "postgresql://USER:PASSWORD@HOST:PORT/DBNAME or \"host=... dbname=...\"");
}

void RequireOneStore(const std::string& command, const std::string& db, const std::string& store) {
  if (db.empty() == store.empty()) {
    throw CLI::ValidationError(command,
                               "give the model store: --db FILE (SQLite) or --store "
                               "postgresql://... (PostgreSQL), not both");
  }
}

ChosenStore OpenChosenStore(const std::string& command, const StoreChoice& choice,
                            bool create_if_missing) {
  RequireOneStore(command, choice.db, choice.store);
  if (!choice.db.empty()) {
    return {std::make_unique<SqliteModelStore>(
                choice.db, SqliteModelStoreOptions{.create_if_missing = create_if_missing}),
            choice.db};
  }
  return {std::make_unique<PostgresModelStore>(choice.store), RedactedTarget(choice.store)};
}

}  // namespace orbit::cli
