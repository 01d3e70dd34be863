// ServerProcess: a real `orbit serve` process on a loopback port, for integration tests.
//
//   ServerProcess server;                      // temp database, free port, no tokens
//   auto channel = grpc::CreateChannel(server.address(), grpc::InsecureChannelCredentials());
//
// The destructor stops the server (SIGTERM, then SIGKILL after 10 s) and removes the temporary
// database it created. A server still running that does not then exit with 0 (it crashed, hung,
// or a sanitizer reported at its exit) fails the current test, with the server's log.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "tests/support/test_data.h"

namespace orbit::testing {

struct ServerProcessOptions {
  // The binary whose `serve` runs: the `orbit` tool, or `orbit-server`
  // (tests/cli/server_main_test.cc).
  std::string binary = OrbitBinary();
  // The model store; a fresh file in a temporary folder when unset (removed afterwards).
  std::optional<std::filesystem::path> database = std::nullopt;
  // A PostgreSQL model store (`--store`, a connection string) instead of the SQLite file.
  std::optional<std::string> store = std::nullopt;
  std::string listen = "127.0.0.1:0";  // port 0: the server picks a free one
  int workers = 2;                     // --workers
  std::optional<std::filesystem::path> tokens_file = std::nullopt;
  std::optional<std::filesystem::path> tls_cert = std::nullopt;
  std::optional<std::filesystem::path> tls_key = std::nullopt;
  // --metrics-listen 127.0.0.1:0: the Prometheus endpoint on a free loopback port.
  bool metrics = false;
  // The server's descriptor limit (RLIMIT_NOFILE, soft and hard, as `ulimit -n` sets it);
  // unset: inherited.
  std::optional<int> descriptor_limit = std::nullopt;
  std::vector<std::string> extra_args =
      {};  // further `orbit serve` flags, e.g. {"--max-sessions", "2"}
  // What the constructor waits for: the server serving ("listening on"), or only its start of
  // loading the store ("loading the store"; address() is then `listen` as given).
  enum class Until { kServing, kLoading };
  Until wait_until = Until::kServing;
};

// Writes `lines` to the token file `file`, readable and writable by its owner alone (mode 600),
// as `orbit serve --tokens` requires.
void WriteTokenFile(const std::filesystem::path& file, const std::string& lines);

// Writes a self-signed certificate for `subject_alt_names` (e.g. "DNS:orbit.test" or
// "DNS:localhost,IP:127.0.0.1") to dir/cert.pem and its key to dir/key.pem, with openssl.
// Throws std::runtime_error when openssl fails.
void MakeSelfSignedCertificate(const std::filesystem::path& dir, const std::string& common_name,
                               const std::string& subject_alt_names);

// Options of a server with TLS and tokens, its files written to `dir`: a certificate for `host`
// (dir/cert.pem, as MakeSelfSignedCertificate), a token file granting `admin_token` the admin
// role and `reader_token` the recognize role, and dir/reader.token holding the reader's token
// behind a comment line, as an operator hands it to a device.
ServerProcessOptions SecuredServerOptions(const std::filesystem::path& dir, const std::string& host,
                                          const std::string& admin_token,
                                          const std::string& reader_token);

class ServerProcess {
 public:
  // Starts the server and waits (up to 60 s) until it says it is listening (or loading, as
  // options.wait_until says).
  // Throws std::runtime_error with the server's log when it exits or does not start in time.
  explicit ServerProcess(ServerProcessOptions options = {});
  ~ServerProcess();

  ServerProcess(const ServerProcess&) = delete;
  ServerProcess& operator=(const ServerProcess&) = delete;

  // "127.0.0.1:PORT", the bound port.
  const std::string& address() const { return address_; }
  int port() const { return port_; }
  const std::filesystem::path& database() const { return database_; }
  // "127.0.0.1:PORT" of the metrics endpoint (with options.metrics), "" without.
  const std::string& metrics_address() const { return metrics_address_; }
  pid_t pid() const { return pid_; }

  // Sends `signal` and waits up to `timeout` for the process to exit. Returns its exit code, or
  // 128 + signal number when a signal ended it, or -1 when it is still running at the timeout.
  int Stop(int signal, std::chrono::seconds timeout = std::chrono::seconds(15));

  // Everything the server printed on stderr so far.
  std::string Log() const;

 private:
  std::filesystem::path temp_dir_;
  std::filesystem::path database_;
  std::filesystem::path log_file_;
  std::string address_;
  std::string metrics_address_;
  int port_ = 0;
  pid_t pid_ = -1;
  bool owns_database_ = false;
};

// Runs `orbit serve` with `args` expecting it to refuse to start; returns its exit code and log.
struct RefusedStart {
  int exit_code = 0;
  std::string log;
};
RefusedStart StartServerExpectingRefusal(const std::vector<std::string>& args);

}  // namespace orbit::testing
