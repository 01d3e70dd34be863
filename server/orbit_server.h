// OrbitServer: the recognition service, assembled: the model store and its index, the Recognition
// and Models services, health checking (grpc.health.v1), server reflection, limits, access
// control, TLS, the idle-session sweeper, metrics (with their Prometheus endpoint when
// config.metrics_listen is set), and a graceful shutdown.
//
//   OrbitServer server(config);      // serving once constructed
//   ... wait for SIGTERM ...
//   server.Shutdown();               // health NOT_SERVING, sessions ended, calls drained
//
// On a PostgreSQL store shared by replicas, the server also follows the changes the others
// commit (server/model_change_follower.h) and reports NOT_SERVING while it has lost the store
// for longer than config.store_grace_seconds.
//
// Thread-safe: Shutdown() may be called from any thread, more than once.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>  // std::once_flag
#include <string>
#include <thread>

#include <grpcpp/grpcpp.h>

#include "core/base/mutex.h"
#include "server/access_control.h"
#include "server/audit_log.h"
#include "server/server_config.h"
#include "server/serving_gate.h"
#include "storage/model_store.h"

namespace orbit::server {

class MetricsEndpoint;
class ModelCatalogue;
class ModelChangeFollower;
class ModelsService;
class RecognitionService;
class RejectionCalibrator;
class ServerMetrics;
class SessionRegistry;
class WorkerPool;

class OrbitServer {
 public:
  // Opens (creating if needed) the store, starts listening (health NOT_SERVING, Orbit calls
  // UNAVAILABLE), indexes the store's objects, calibrates rejection and starts serving.
  // Throws std::invalid_argument as ValidateServerConfig (server_config.h), and
  // std::runtime_error with a message for the operator when the configuration is unsafe
  // (no tokens on a non-loopback address), a file cannot be read, the store cannot be opened, or
  // the address cannot be bound; a metrics address that is malformed or cannot be bound is a
  // std::runtime_error beginning "--metrics-listen: ". Nothing is served then.
  explicit OrbitServer(const ServerConfig& config);
  ~OrbitServer();

  OrbitServer(const OrbitServer&) = delete;
  OrbitServer& operator=(const OrbitServer&) = delete;

  // The port bound (useful with port 0).
  int port() const { return port_; }
  // The address clients should use, HOST:PORT with the bound port.
  std::string address() const;
  // The metrics endpoint's HOST:PORT with the bound port; "" without config.metrics_listen.
  std::string metrics_address() const;

  // The descriptor variant of every model and session (ServerConfig::variant, resolved).
  DescriptorVariant variant() const { return *config_.variant; }

  // Health goes NOT_SERVING, new sessions are refused, open sessions end with UNAVAILABLE, and
  // gRPC stops after letting calls finish for up to shutdown_grace_seconds; the metrics endpoint
  // stops before the workers do.
  void Shutdown() ABSL_LOCKS_EXCLUDED(sweeper_mutex_);

  // Reads the token file again (on SIGHUP; the server also does when the file changes): the
  // new grants hold from the next call, and the sessions and enrollments of a token whose grant
  // is gone, replaced or lessened end with UNAUTHENTICATED. A bad file is reported on stderr and
  // the grants in force stay. Nothing without --tokens.
  void ReloadCredentials();

 private:
  void SweepIdleSessions() ABSL_LOCKS_EXCLUDED(sweeper_mutex_);
  // Health of every service: SERVING when `fit`, NOT_SERVING otherwise.
  void SetServing(bool fit);

  ServerConfig config_;
  std::unique_ptr<AuditLog> audit_;  // before access_, which records refusals in it
  AccessControl access_;
  ServingGate gate_;  // opened once the index is loaded
  std::unique_ptr<ServerMetrics> metrics_;
  std::unique_ptr<ModelStore> store_;
  std::unique_ptr<ModelCatalogue> catalogue_;
  std::unique_ptr<RejectionCalibrator> calibrator_;
  std::unique_ptr<WorkerPool> pool_;
  std::unique_ptr<WorkerPool> bulk_pool_;
  std::unique_ptr<SessionRegistry> registry_;
  std::unique_ptr<SessionRegistry> enrollments_;  // the open Enroll streams
  std::unique_ptr<RecognitionService> recognition_;
  std::unique_ptr<ModelsService> models_;
  // Reads the registry, sessions, catalogue and pools when scraped: destroyed (stopped) first.
  std::unique_ptr<MetricsEndpoint> metrics_endpoint_;
  std::unique_ptr<grpc::Server> server_;
  int port_ = 0;

  Mutex sweeper_mutex_;  // held by the sweeper while it closes idle sessions
  CondVar sweeper_wake_;
  bool stopping_ ABSL_GUARDED_BY(sweeper_mutex_) = false;
  std::thread sweeper_;
  std::once_flag shutdown_once_;
  // With a PostgreSQL store: follows what other replicas write. Uses the catalogue and the
  // health service: declared last, destroyed (stopped) first.
  std::unique_ptr<ModelChangeFollower> follower_;
};

}  // namespace orbit::server
