#include "server/orbit_server.h"

#include <algorithm>
#include <chrono>
#include <iostream>
#include <stdexcept>

#include <grpcpp/ext/proto_server_reflection_plugin.h>
#include <grpcpp/health_check_service_interface.h>

#include "core/base/parallel_for.h"
#include "core/engines/product_pipeline.h"
#include "orbit/version.h"
#include "server/error_status.h"
#include "server/metrics_endpoint.h"
#include "server/model_catalogue.h"
#include "server/model_change_follower.h"
#include "server/models_service.h"
#include "server/recognition_service.h"
#include "server/server_metrics.h"
#include "server/session_engine.h"
#include "server/session_registry.h"
#include "server/tls_credentials.h"
#include "server/worker_pool.h"
#include "storage/postgres_model_store.h"
#include "storage/sqlite_model_store.h"
#include "storage/view_index_loading.h"

namespace orbit::server {
namespace {

// The bulk workers' niceness (WorkerPool): enough that CFS gives a session's descriptor frame
// the core at once when an enrollment or an image is being processed (weight 110 against 1024).
constexpr int kBulkWorkerNice = 10;

// The SQLite file (created when missing).
std::unique_ptr<ModelStore> OpenSqliteStore(const ServerConfig& config) {
  SqliteModelStoreOptions options;
  options.create_if_missing = true;
  return std::make_unique<SqliteModelStore>(config.database, options);
}

}  // namespace

OrbitServer::OrbitServer(const ServerConfig& config) : config_(config) {
  ValidateServerConfig(config_);
  audit_ = std::make_unique<AuditLog>(config_.audit_log);
  if (config_.tokens_file) {
    access_ = AccessControl::FromFile(*config_.tokens_file);
    for (const std::string& warning : access_.warnings()) {
      std::cerr << "orbit serve: warning: " << warning << std::endl;
    }
    access_.AuditTo(audit_.get());
    if (!config_.tls_cert && !IsLoopbackAddress(config_.listen)) {
      std::cerr << "orbit serve: warning: tokens on " << config_.listen
                << " travel in clear text: anyone on the path can read and reuse them. Give "
                   "--tls-cert and --tls-key, or serve behind a proxy that terminates TLS"
                << std::endl;
    }
  } else if (!IsLoopbackAddress(config_.listen) && !config_.allow_remote_without_tokens) {
    throw std::runtime_error(
        "refusing to serve " + config_.listen +
        " without tokens: anyone reaching it could enroll and delete objects. Give --tokens FILE,"
        " listen on 127.0.0.1, or pass --allow-remote-without-tokens if you really mean it");
  }
  metrics_ = std::make_unique<ServerMetrics>();
  // On a shared PostgreSQL store, the change log's position is read before the index is
  // loaded, and followed from there once serving: nothing committed in between is missed.
  PostgresModelStore* shared_store = nullptr;
  std::int64_t loaded_after_seq = 0;
  if (!config_.store.empty()) {
    auto postgres = std::make_unique<PostgresModelStore>(config_.store);
    shared_store = postgres.get();
    loaded_after_seq = postgres->LatestChangeSeq();
    store_ = std::move(postgres);
  } else {
    store_ = OpenSqliteStore(config_);
  }
  if (!config_.variant) config_.variant = StoreVariant(*store_).value_or(Product().variant);
  config_.session_defaults.options.candidates_above =
      config_.candidates_above.value_or(ProductCandidatesAbove(*config_.variant));
  config_.session_defaults.options.false_accept_rate =
      config_.false_accept_rate.value_or(ProductFalseAcceptRate(*config_.variant));
  const int cpus = AvailableCpus();
  // The store's load (and a replica's reload) builds the index on every CPU: a server serves
  // nothing before its first load ends (docs/design.md#view-index).
  ViewIndexOptions index = config_.index;
  index.build_threads = std::max(index.build_threads, cpus);
  catalogue_ =
      std::make_unique<ModelCatalogue>(*store_, *config_.variant, index, metrics_->store_writes());
  catalogue_->PrepareSnapshotsWith(PrepareForSessions(config_.session_defaults));
  calibrator_ = std::make_unique<RejectionCalibrator>(catalogue_->Snapshot());
  pool_ = std::make_unique<WorkerPool>(config_.worker_threads > 0 ? config_.worker_threads : cpus,
                                       0, config_.limits.max_queued_calls);
  bulk_pool_ = std::make_unique<WorkerPool>(
      config_.bulk_worker_threads > 0 ? config_.bulk_worker_threads : std::max(1, cpus / 2),
      kBulkWorkerNice, config_.limits.max_queued_calls);
  registry_ = std::make_unique<SessionRegistry>(
      StreamLimits{.max_open = config_.limits.max_sessions,
                   .max_open_per_token = config_.limits.max_sessions_per_token});
  enrollments_ =
      std::make_unique<SessionRegistry>(StreamLimits{.max_open = config_.limits.max_enrollments,
                                                     .noun = "enrollment",
                                                     .flag = "--max-enrollments",
                                                     .activity = "a message"});
  recognition_ = std::make_unique<RecognitionService>(
      SessionEnvironment{*catalogue_, *calibrator_, *pool_, *bulk_pool_, *registry_, config_.limits,
                         config_.session_defaults, *metrics_, gate_},
      access_);
  models_ = std::make_unique<ModelsService>(ModelsEnvironment{
      *catalogue_, *pool_, *bulk_pool_, access_, config_.limits, config_.session_defaults,
      kOrbitVersion, *metrics_, gate_, *enrollments_, *audit_, *calibrator_});
  metrics_->WatchSessions(*registry_);
  metrics_->WatchIndex(*catalogue_);
  metrics_->WatchWorkers(*pool_, *bulk_pool_);
  metrics_->WatchConnections();
  if (!config_.metrics_listen.empty()) {  // before gRPC: a bad address serves nothing at all
    try {
      metrics_endpoint_ = std::make_unique<MetricsEndpoint>(config_.metrics_listen, *metrics_);
    } catch (const std::exception& e) {
      throw std::runtime_error(std::string("--metrics-listen: ") + e.what());
    }
  }

  grpc::EnableDefaultHealthCheckService(true);
  grpc::reflection::InitProtoReflectionServerBuilderPlugin();
  grpc::ServerBuilder builder;
  builder.AddListeningPort(
      config_.listen,
      ServerTlsCredentials({config_.tls_cert, config_.tls_key, config_.tls_client_ca}), &port_);
  builder.SetMaxReceiveMessageSize(config_.limits.max_message_bytes);
  ApplyConnectionLimits(config_.connections, builder);
  builder.RegisterService(recognition_.get());
  builder.RegisterService(models_.get());
  server_ = builder.BuildAndStart();
  if (!server_ || port_ == 0) {
    throw std::runtime_error("cannot listen on " + config_.listen +
                             " (address in use, or not an address of this machine?)");
  }
  // Listening, NOT_SERVING and refusing Orbit calls (UNAVAILABLE) while the index loads: a
  // balancer's health check and a client get an answer instead of a refused connection.
  SetServing(false);
  try {
    catalogue_->Load();
    calibrator_->For(catalogue_->Snapshot());  // the first calibration, before any session
  } catch (...) {
    server_->Shutdown();
    throw;
  }
  gate_.Open();
  SetServing(true);
  sweeper_ = std::thread([this] { SweepIdleSessions(); });
  if (shared_store != nullptr) {
    ModelChangeFollowerOptions follow;
    follow.store_grace = std::chrono::seconds(config_.store_grace_seconds);
    follow.on_fitness = [this](bool fit) { SetServing(fit); };
    follow.on_event = [](const std::string& message) {
      std::cerr << "orbit serve: " << message << std::endl;
    };
    follow.on_applied = [lag = &metrics_->change_lag_seconds()](const ModelChange& change) {
      if (const auto committed = CommittedTime(change)) {
        lag->Observe(std::max(
            0.0,
            std::chrono::duration<double>(std::chrono::system_clock::now() - *committed).count()));
      }
    };
    follower_ = std::make_unique<ModelChangeFollower>(*shared_store, config_.store, *catalogue_,
                                                      loaded_after_seq, std::move(follow));
  }
}

void OrbitServer::SetServing(bool fit) {
  grpc::HealthCheckServiceInterface* health = server_->GetHealthCheckService();
  health->SetServingStatus("", fit);
  health->SetServingStatus(v1::Recognition::service_full_name(), fit);
  health->SetServingStatus(v1::Models::service_full_name(), fit);
}

OrbitServer::~OrbitServer() { Shutdown(); }

std::string OrbitServer::address() const {
  const std::string& listen = config_.listen;
  return listen.substr(0, listen.rfind(':')) + ":" + std::to_string(port_);
}

std::string OrbitServer::metrics_address() const {
  return metrics_endpoint_ ? metrics_endpoint_->address() : std::string();
}

void OrbitServer::SweepIdleSessions() {
  const auto timeout = std::chrono::seconds(config_.limits.idle_timeout_seconds);
  MutexLock lock(&sweeper_mutex_);
  for (int sweep = 1;; ++sweep) {
    const auto next_sweep = std::chrono::steady_clock::now() + std::chrono::milliseconds(250);
    while (!stopping_ && sweeper_wake_.WaitUntil(&sweeper_mutex_, next_sweep)) {
    }
    if (stopping_) return;
    // The token file is looked at every second: an operator's edit holds without a signal.
    if (sweep % 4 == 0 && access_.FileChanged()) ReloadCredentials();
    const auto now = std::chrono::steady_clock::now();
    registry_->CloseIdle(now - timeout, config_.limits.idle_timeout_seconds);
    enrollments_->CloseIdle(
        now - std::chrono::seconds(config_.limits.enrollment_idle_timeout_seconds),
        config_.limits.enrollment_idle_timeout_seconds);
  }
}

void OrbitServer::ReloadCredentials() {
  if (!access_.enabled()) return;
  try {
    const std::vector<std::string> revoked = access_.Reload();
    std::cerr << "orbit serve: tokens reloaded from " << config_.tokens_file->string() << ": "
              << access_.token_count() << " in force";
    for (std::size_t i = 0; i < revoked.size(); ++i) {
      std::cerr << (i == 0 ? "; revoked: " : ", ") << revoked[i];
    }
    std::cerr << std::endl;
    for (const std::string& warning : access_.warnings()) {
      std::cerr << "orbit serve: warning: " << warning << std::endl;
    }
    const grpc::Status status(grpc::StatusCode::UNAUTHENTICATED,
                              "the token of this stream was revoked");
    registry_->CloseTokens(revoked, status);
    enrollments_->CloseTokens(revoked, status);
  } catch (const std::exception& e) {
    std::cerr << "orbit serve: the token file was not reloaded, the tokens in force stay: "
              << e.what() << std::endl;
  }
}

void OrbitServer::Shutdown() {
  std::call_once(shutdown_once_, [this] {
    follower_.reset();  // before health is shut down: it could set SERVING again
    server_->GetHealthCheckService()->Shutdown();  // every service NOT_SERVING, for good
    registry_->CloseAll(ShuttingDown());
    enrollments_->CloseAll(ShuttingDown());
    {
      MutexLock lock(&sweeper_mutex_);
      stopping_ = true;
    }
    sweeper_wake_.SignalAll();
    sweeper_.join();
    // Work still queued is answered UNAVAILABLE now (docs/design.md#work-queues); work running
    // gets the grace, then gRPC cancels its call, and a Recognize batch stops at its next frame.
    pool_->Stop();
    bulk_pool_->Stop();
    server_->Shutdown(std::chrono::system_clock::now() +
                      std::chrono::seconds(config_.shutdown_grace_seconds));
    metrics_endpoint_.reset();  // its scrapes read the pools
    pool_.reset();              // joins the threads once their running tasks end
    bulk_pool_.reset();
  });
}

}  // namespace orbit::server
