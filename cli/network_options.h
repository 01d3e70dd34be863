// The options every networked subcommand shares (`orbit enroll|recognize|info|demo`, and
// `orbit import|list|delete --server`): where the server is, how to prove who we are, and how
// long to wait.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "client/connection.h"

namespace orbit::cli {

struct NetworkOptions {
  std::string server;           // HOST:PORT
  std::string token;            // --token or $ORBIT_TOKEN
  std::string token_file;       // --token-file: the token on its first line; wins over token
  std::string tls_ca;           // --tls-ca: root certificate(s), PEM; TLS when given
  std::string tls_server_name;  // --tls-server-name: the name the certificate carries
  double timeout_seconds = 10;  // deadline of each unary call
};

// Adds --server (required when `server_required`), --token, --token-file, --tls-ca,
// --tls-server-name and --timeout to `command`; returns the --server option, e.g. for
// `excludes` with --db.
CLI::Option* AddNetworkOptions(CLI::App& command, NetworkOptions& options, bool server_required);

// For subcommands that work on a model store file or on a server (`import`, `list`, `delete`):
// adds --db FILE and the network options above, the two mutually exclusive.
void AddDatabaseOrServerOptions(CLI::App& command, std::string& db, NetworkOptions& network);

// True when the command is to use the server, false for the file. Throws
// std::invalid_argument when neither --db nor --server was given.
bool UsesServer(const std::string& db, const NetworkOptions& network);

// The connection those options describe; reads the token file. Throws std::runtime_error when
// the token file cannot be read.
ConnectionOptions ToConnectionOptions(const NetworkOptions& options);

}  // namespace orbit::cli
