// orbit delete: removes one object, with all its views, from a model store.
#include <iostream>
#include <memory>
#include <string>

#include "client/cli/commands.h"
#include "storage/sqlite_model_store.h"

namespace orbit::cli {
namespace {

struct DeleteOptions {
  std::string db;
  std::string name;
};

int RunDelete(const DeleteOptions& options) {
  SqliteModelStore store(options.db);
  const std::optional<ObjectSummary> object = store.Find(options.name);
  if (!object) {
    std::cerr << "orbit delete: no object named \"" << options.name << "\" in " << options.db
              << "\n";
    return 1;
  }
  store.Delete(object->id);
  std::cout << "deleted " << object->name << " (id " << object->id << ", " << object->view_count
            << " views)\n";
  return 0;
}

}  // namespace

void AddDeleteCommand(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<DeleteOptions>();
  CLI::App* command = app.add_subcommand(
      "delete", "Delete the object NAME and all its views from a model store. Exit status 1\n"
                "when there is no such object.");
  command->add_option("--db", options->db, "model store file")->required();
  command->add_option("NAME", options->name, "object name")->required();
  command->callback([options, &exit_code] { exit_code = RunDelete(*options); });
}

}  // namespace orbit::cli
