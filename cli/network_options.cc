#include "cli/network_options.h"

#include <cmath>
#include <stdexcept>

namespace orbit::cli {

CLI::Option* AddNetworkOptions(CLI::App& command, NetworkOptions& options, bool server_required) {
  CLI::Option* server =
      command.add_option("--server", options.server, "the Orbit server, HOST:PORT");
  if (server_required) server->required();
  command.add_option("--token", options.token, "bearer token (default: $ORBIT_TOKEN)")
      ->envname("ORBIT_TOKEN");
  // Not exclusive with --token: a token file named on the command line beats an $ORBIT_TOKEN
  // left in the environment.
  command
      .add_option("--token-file", options.token_file,
                  "file whose first line is the token (wins over --token)")
      ->check(CLI::ExistingFile);
  command
      .add_option("--tls-ca", options.tls_ca,
                  "PEM root certificate(s) of the server's certificate: use TLS")
      ->check(CLI::ExistingFile);
  command.add_option("--tls-server-name", options.tls_server_name,
                     "name on the server's certificate when it differs from HOST");
  command.add_option("--timeout", options.timeout_seconds, "deadline of each call, in seconds")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  return server;
}

void AddDatabaseOrServerOptions(CLI::App& command, std::string& db, NetworkOptions& network) {
  CLI::Option* file = command.add_option("--db", db, "model store file (SQLite)");
  CLI::Option* server = AddNetworkOptions(command, network, /*server_required=*/false);
  file->excludes(server);
}

bool UsesServer(const std::string& db, const NetworkOptions& network) {
  if (db.empty() && network.server.empty()) {
    throw std::invalid_argument("give --db FILE (a local model store) or --server HOST:PORT");
  }
  return !network.server.empty();
}

ConnectionOptions ToConnectionOptions(const NetworkOptions& options) {
  ConnectionOptions connection;
  connection.address = options.server;
  connection.token = options.token_file.empty() ? options.token : ReadTokenFile(options.token_file);
  connection.tls_root_certificates_file = options.tls_ca;
  connection.tls_server_name = options.tls_server_name;
  connection.unary_deadline =
      std::chrono::milliseconds(std::llround(options.timeout_seconds * 1000));
  return connection;
}

}  // namespace orbit::cli
