// OrbitServer: the recognition service, assembled: the model store and its index, the Recognition
// and Models services, health checking (grpc.health.v1), server reflection, limits, access
// control, TLS, the idle-session sweeper, and a graceful shutdown.
//
//   OrbitServer server(config);      // serving once constructed
//   ... wait for SIGTERM ...
//   server.Shutdown();               // health NOT_SERVING, sessions ended, calls drained
//
// Thread-safe: Shutdown() may be called from any thread, more than once.
#pragma once

#include <atomic>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include <grpcpp/grpcpp.h>

#include "server/access_control.h"
#include "server/server_config.h"
#include "storage/model_store.h"

namespace orbit::server {

class ModelCatalogue;
class ModelsService;
class RecognitionService;
class SessionRegistry;
class WorkerPool;

class OrbitServer {
 public:
  // Opens (creating if needed) the store, indexes its objects and starts serving.
  // Throws std::invalid_argument as ValidateServerConfig (server_config.h), and
  // std::runtime_error with a message for the operator when the configuration is unsafe
  // (no tokens on a non-loopback address), a file cannot be read, the store cannot be opened, or
  // the address cannot be bound.
  explicit OrbitServer(const ServerConfig& config);
  ~OrbitServer();

  OrbitServer(const OrbitServer&) = delete;
  OrbitServer& operator=(const OrbitServer&) = delete;

  // The port bound (useful with port 0).
  int port() const { return port_; }
  // The address clients should use, HOST:PORT with the bound port.
  std::string address() const;

  // Health goes NOT_SERVING, new sessions are refused, open sessions end with UNAVAILABLE, and
  // gRPC stops after letting calls finish for up to shutdown_grace_seconds.
  void Shutdown();

 private:
  void SweepIdleSessions();

  ServerConfig config_;
  AccessControl access_;
  std::unique_ptr<ModelStore> store_;
  std::unique_ptr<ModelCatalogue> catalogue_;
  std::unique_ptr<WorkerPool> pool_;
  std::unique_ptr<WorkerPool> bulk_pool_;
  std::unique_ptr<SessionRegistry> registry_;
  std::unique_ptr<RecognitionService> recognition_;
  std::unique_ptr<ModelsService> models_;
  std::unique_ptr<grpc::Server> server_;
  int port_ = 0;

  std::mutex sweeper_mutex_;
  std::condition_variable sweeper_wake_;
  bool stopping_ = false;
  std::thread sweeper_;
  std::once_flag shutdown_once_;
};

}  // namespace orbit::server
