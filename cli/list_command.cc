// orbit list: the objects of a model store, one per line.
#include <iostream>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/network_options.h"
#include "cli/object_summary.h"
#include "client/models_client.h"
#include "storage/sqlite_model_store.h"

namespace orbit::cli {
namespace {

struct ListOptions {
  std::string db;
  NetworkOptions network;
  bool json = false;
};

// `ID NAME VARIANT VIEWS UPDATED_AT`: space-separated (names never hold spaces), so the plain
// output is easy to read and to cut.
std::string PlainLine(const ObjectSummary& object) {
  return std::to_string(object.id) + " " + object.name + " " +
         std::string(VariantName(object.variant)) + " " + std::to_string(object.view_count) + " " +
         object.updated_at;
}

std::string JsonLine(const ObjectSummary& object) {
  const nlohmann::ordered_json line = {
      {"id", object.id},
      {"name", object.name},
      {"variant", VariantName(object.variant)},
      {"views", object.view_count},
      {"created_at", object.created_at},
      {"updated_at", object.updated_at},
      {"metadata", nlohmann::json::parse(object.metadata)},
  };
  return line.dump();
}

int RunList(const ListOptions& options) {
  auto print = [&](const ObjectSummary& object) {
    std::cout << (options.json ? JsonLine(object) : PlainLine(object)) << "\n";
  };
  if (UsesServer(options.db, options.network)) {
    const Connection connection(ToConnectionOptions(options.network));
    for (const v1::ObjectInfo& object : ModelsClient(connection).ListAllObjects()) {
      print(SummaryOf(object));
    }
    return 0;
  }
  SqliteModelStore store(options.db);
  ListRequest request{.after_id = 0, .limit = 1000};
  for (;;) {
    const std::vector<ObjectSummary> page = store.List(request);
    if (page.empty()) return 0;
    for (const ObjectSummary& object : page) print(object);
    request.after_id = page.back().id;
  }
}

}  // namespace

void AddListCommand(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<ListOptions>();
  CLI::App* command = app.add_subcommand(
      "list",
      "List the objects of a model store (--db) or a server (--server) in id order, one per\n"
      "line:\n"
      "`ID NAME VARIANT VIEWS UPDATED_AT`, or with --json one JSON object per line with\n"
      "id, name, variant, views, created_at, updated_at and metadata.");
  AddDatabaseOrServerOptions(*command, options->db, options->network);
  command->add_flag("--json", options->json, "one JSON object per line");
  command->callback([options, &exit_code] { exit_code = RunList(*options); });
}

}  // namespace orbit::cli
