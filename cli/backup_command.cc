// orbit backup: a consistent copy of a model store, safe while a server uses it.
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "storage/sqlite_model_store.h"
#include "storage/store_files.h"

namespace orbit::cli {
namespace {

struct BackupOptions {
  std::string db;
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
  SqliteModelStore store(options.db);
  store.Backup(options.to);
  std::cout << "backed up " << options.db << " to " << options.to << " ("
            << std::filesystem::file_size(options.to) << " bytes)\n";
  return 0;
}

}  // namespace

void AddBackupCommand(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<BackupOptions>();
  CLI::App* command = app.add_subcommand(
      "backup",
      "Copy a model store to a file with SQLite's online backup: consistent even while a\n"
      "server or an import writes to the store. The copy replaces --to atomically once it is\n"
      "complete and checked; it opens as a model store like the original, and has the\n"
      "store's file mode. --to may name an earlier backup (or an empty file); anything else\n"
      "is refused unless --force.");
  command->add_option("--db", options->db, "model store file")->required();
  command->add_option("--to", options->to, "destination file")->required();
  command->add_flag("--force", options->force,
                    "replace --to even when it is not an Orbit model store");
  command->callback([options, &exit_code] { exit_code = RunBackup(*options); });
}

}  // namespace orbit::cli
