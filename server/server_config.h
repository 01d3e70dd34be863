// Everything `orbit serve` can be told (flags, environment, config file: cli/
// serve_command.cc), with the defaults a single edge server should start with.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "core/index/view_index.h"
#include "server/connection_limits.h"
#include "server/session_settings.h"

namespace orbit::server {

struct ServerConfig {
  std::filesystem::path database;  // the SQLite model store; created when missing
  // A PostgreSQL model store instead (storage/postgres_model_store.h): a libpq connection
  // string, postgresql://USER:PASSWORD@HOST:PORT/DBNAME or "host=... dbname=...". Several
  // servers may share it. Empty: the SQLite store in `database`.
  std::string store;
  // With `store`: how long the replica may lose the store before its health reports
  // NOT_SERVING (its models may be stale; server/model_change_follower.h).
  int store_grace_seconds = 10;
  std::string listen = "127.0.0.1:50051";            // HOST:PORT; port 0 picks a free port
  std::optional<std::filesystem::path> tokens_file;  // server/token_file.h
  // Where administrative calls and refused authentications are recorded, a JSON line each
  // (server/audit_log.h): a file, or "-" for stderr.
  std::string audit_log = "-";
  std::optional<std::filesystem::path> tls_cert;  // PEM certificate chain (with tls_key)
  std::optional<std::filesystem::path> tls_key;   // PEM private key
  // PEM CA bundle: mutual TLS, every client shows a certificate it signed
  // (server/tls_credentials.h).
  std::optional<std::filesystem::path> tls_client_ca;
  // Serving without tokens on a non-loopback address exposes enrollment and deletion to anyone
  // who can reach the port: refused unless explicitly allowed.
  bool allow_remote_without_tokens = false;
  // Of every model and session. Unset: the variant of the objects the store holds (StoreVariant),
  // or the product's (core/engines/product_pipeline.h) for an empty store, so a store built with
  // an older default keeps serving without a flag.
  std::optional<DescriptorVariant> variant;
  // Sessions' HMM scores only candidate objects once the model set holds more than this many
  // (EngineOptions::candidates_above of session_defaults, set by OrbitServer once the variant is
  // known). Unset: ProductCandidatesAbove(variant).
  std::optional<int> candidates_above;
  // The calibrated rule's target false-accept rate of sessions that ask for none
  // (EngineOptions::false_accept_rate of session_defaults, set by OrbitServer once the variant
  // is known). Unset: ProductFalseAcceptRate(variant).
  std::optional<double> false_accept_rate;
  ViewIndexOptions index{.search = SearchMode::kKdTree};
  SessionSettings session_defaults;
  ServerLimits limits;
  ConnectionLimits connections;
  int worker_threads = 0;  // descriptor frames and short calls; 0: one per core
  // Work that may take long: frames and views sent as images (decoding), enrollments and added
  // views (describing, the store's fsync). On workers of its own, so that it never delays
  // another session's descriptor frames. 0: half the cores, at least one.
  int bulk_worker_threads = 0;
  int shutdown_grace_seconds = 5;  // SIGTERM: time open calls get to end cleanly
  // HOST:PORT of the Prometheus metrics endpoint, http://HOST:PORT/metrics
  // (server/metrics_endpoint.h); empty: none. Metrics are counted either way.
  std::string metrics_listen;

  // Multi-line, human-readable account of the configuration in force (no secrets: token and
  // key files are named, not read), printed once at start-up.
  std::string Describe() const;
};

// The rules `orbit serve` checks at start-up, before anything is opened: the default session
// must be one the server would admit (the HMM memory rule of session_settings.h, engine options
// in range), and `store`, when given, must be a connection string. Throws std::invalid_argument
// naming the option. OrbitServer calls it.
void ValidateServerConfig(const ServerConfig& config);

// True for an IPv4 address in 127.0.0.0/8, ::1 and "localhost" (HOST of a HOST:PORT address,
// brackets allowed). A host name is not resolved: "127.example.com" is not loopback.
bool IsLoopbackAddress(const std::string& host_and_port);

}  // namespace orbit::server
