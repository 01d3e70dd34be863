// orbit restore: a backup (orbit backup) back into an empty model store.
#include <cstdint>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/store_choice.h"
#include "storage/sqlite_model_store.h"

namespace orbit::cli {
namespace {

struct RestoreOptions {
  std::string from;
  StoreChoice into;
};

// How many objects `store` holds.
std::int64_t CountObjects(ModelStore& store) {
  std::int64_t count = 0;
  ListRequest page{.after_id = 0, .limit = kMaxListLimit};
  for (std::vector<ObjectSummary> objects = store.List(page); !objects.empty();
       objects = store.List(page)) {
    count += static_cast<std::int64_t>(objects.size());
    page.after_id = objects.back().id;
  }
  return count;
}

int RunRestore(const RestoreOptions& options) {
  SqliteModelStore backup(options.from);
  const ChosenStore target = OpenChosenStore("restore", options.into, /*create_if_missing=*/true);
  target.store->RestoreFrom(backup);
  std::cout << "restored " << options.from << " into " << target.name << " ("
            << CountObjects(*target.store) << " objects)\n";
  return 0;
}

}  // namespace

void AddRestoreCommand(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<RestoreOptions>();
  CLI::App* command = app.add_subcommand(
      "restore",
      "Copy a backup (orbit backup --to) into an empty model store: a SQLite file (--db,\n"
      "created when missing, mode 0600) or a PostgreSQL database (--store). One transaction:\n"
      "ids, names, times, metadata, views and thumbnails as in the backup, or nothing. A store\n"
      "that holds objects is refused. Replicas following the PostgreSQL database index the\n"
      "restored objects as enrollments (docs/operations.md).");
  command->add_option("--from", options->from, "the backup file")->required();
  AddStoreChoiceOptions(*command, options->into, "the model store to fill (SQLite file)");
  command->callback([options, &exit_code] { exit_code = RunRestore(*options); });
}

}  // namespace orbit::cli
