// orbit backup: a consistent copy of a model store, safe while servers use it.
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "cli/store_choice.h"
#include "storage/store_files.h"

namespace orbit::cli {
namespace {

struct BackupOptions {
  StoreChoice from;
  std::string to;
  bool force = false;
};

int RunBackup(const BackupOptions& options) {
  // A mistyped --to must not cost the operator an unrelated file (docs/design.md#file-safety).
  if (!options.force && std::filesystem::exists(options.to) && !HoldsOnlyAStore(options.to)) {
    std::cerr << "orbit backup: --to " << options.to
              << " exists and is not an Orbit model store; pass --force to replace it\n";
    return 1;
  }
  const ChosenStore source = OpenChosenStore("backup", options.from, /*create_if_missing=*/false);
  source.store->Backup(options.to);
  std::cout << "backed up " << source.name << " to " << options.to << " ("
            << std::filesystem::file_size(options.to) << " bytes)\n";
  return 0;
}

}  // namespace

void AddBackupCommand(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<BackupOptions>();
  CLI::App* command = app.add_subcommand(
      "backup",
      "Copy a model store (--db, or --store: PostgreSQL) to a file: one consistent snapshot,\n"
      "even while servers write to the store. The copy is a SQLite model store (open it with\n"
      "--db; `orbit restore` puts it back into either kind of store) with the store file's\n"
      "mode (0600 from PostgreSQL). It replaces --to atomically once complete and checked;\n"
      "--to may name an earlier backup or an empty file, anything else only with --force.\n"
      "Not copied: PostgreSQL's change log (docs/operations.md).");
  AddStoreChoiceOptions(*command, options->from, "model store file (SQLite)");
  command->add_option("--to", options->to, "destination file")->required();
  command->add_flag("--force", options->force,
                    "replace --to even when it is not an Orbit model store");
  command->callback([options, &exit_code] { exit_code = RunBackup(*options); });
}

}  // namespace orbit::cli
