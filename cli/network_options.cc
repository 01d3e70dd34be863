#include "cli/network_options.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace orbit::cli {
namespace {

// The server the user meant, as an example in the messages below: the host they gave (or
// loopback) with the server's default port (`orbit serve --listen`).
std::string ExampleAddress(const std::string& host) {
  return (host.empty() ? std::string("127.0.0.1") : host) + ":50051";
}

// The --server check: empty when `address` is HOST:PORT (an IPv6 host in brackets) with a port
// of 1 to 65535, otherwise what is wrong and the form to give. gRPC would take "127.0.0.1" as
// port 0 and only fail on connecting, with a message that names neither the flag nor the form.
std::string CheckServerAddress(const std::string& address) {
  const std::string form = "give HOST:PORT, e.g. ";
  if (address.empty()) return "no address: " + form + ExampleAddress("");
  std::string host;
  std::string port;
  if (address.front() == '[') {
    const auto close = address.find(']');
    if (close == std::string::npos) {
      return address + " opens an IPv6 host with [ and never closes it: " + form + "[::1]:50051";
    }
    host = address.substr(0, close + 1);
    if (close + 1 == address.size()) {
      return address + " has no port: " + form + ExampleAddress(host);
    }
    if (address[close + 1] != ':') return address + " is not HOST:PORT: " + form + "[::1]:50051";
    port = address.substr(close + 2);
  } else {
    const auto colon = address.rfind(':');
    if (colon == std::string::npos)
      return address + " has no port: " + form + ExampleAddress(address);
    host = address.substr(0, colon);
    port = address.substr(colon + 1);
    if (host.find(':') != std::string::npos) {
      return address + " is ambiguous: write an IPv6 host in brackets, e.g. [::1]:50051";
    }
  }
  if (host.empty() || host == "[]") return address + " has no host: " + form + ExampleAddress("");
  if (port.empty()) return address + " has no port: " + form + ExampleAddress(host);
  if (port.find_first_not_of("0123456789") != std::string::npos) {
    return "port \"" + port + "\" is not a number: " + form + ExampleAddress(host);
  }
  if (port.size() > 5 || std::stoi(port) < 1 || std::stoi(port) > 65535) {
    return "port " + port + " is out of range: give HOST:PORT with a PORT of 1 to 65535";
  }
  return {};
}

}  // namespace

CLI::Option* AddNetworkOptions(CLI::App& command, NetworkOptions& options, bool server_required) {
  CLI::Option* server =
      command.add_option("--server", options.server, "the Orbit server, HOST:PORT");
  server->check(CLI::Validator(CheckServerAddress, "", "HOST:PORT"));
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
