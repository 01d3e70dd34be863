// orbit delete: removes one object, with all its views, from a model store.
#include <iostream>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "cli/network_options.h"
#include "cli/object_summary.h"
#include "client/models_client.h"
#include "client/rpc_error.h"
#include "storage/sqlite_model_store.h"

namespace orbit::cli {
namespace {

struct DeleteOptions {
  std::string db;
  NetworkOptions network;
  std::string name;
};

void PrintDeleted(const ObjectSummary& object) {
  std::cout << "deleted " << object.name << " (id " << object.id << ", " << object.view_count
            << " views)\n";
}

int DeleteOnServer(const DeleteOptions& options) {
  const Connection connection(ToConnectionOptions(options.network));
  try {
    PrintDeleted(SummaryOf(ModelsClient(connection).DeleteObject(ObjectByName(options.name))));
  } catch (const RpcError& e) {
    if (e.code() != grpc::StatusCode::NOT_FOUND) throw;
    std::cerr << "orbit delete: no object named \"" << options.name << "\" on "
              << options.network.server << "\n";
    return 1;
  }
  return 0;
}

int RunDelete(const DeleteOptions& options) {
  if (UsesServer(options.db, options.network)) return DeleteOnServer(options);
  SqliteModelStore store(options.db);
  const std::optional<ObjectSummary> object = store.Find(options.name);
  if (!object) {
    std::cerr << "orbit delete: no object named \"" << options.name << "\" in " << options.db
              << "\n";
    return 1;
  }
  store.Delete(object->id);
  PrintDeleted(*object);
  return 0;
}

}  // namespace

void AddDeleteCommand(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<DeleteOptions>();
  CLI::App* command = app.add_subcommand(
      "delete",
      "Delete the object NAME and all its views from a model store (--db) or a\n"
      "server (--server; admin token). Exit status 1 when there is no such object.");
  AddDatabaseOrServerOptions(*command, options->db, options->network);
  command->add_option("NAME", options->name, "object name")->required();
  command->callback([options, &exit_code] { exit_code = RunDelete(*options); });
}

}  // namespace orbit::cli
