// orbit serve: runs the recognition server on its embedded SQLite store, or on a PostgreSQL store
// that several servers share, until SIGTERM or SIGINT; SIGHUP reloads the token file.
#include <pthread.h>
#include <signal.h>

#include <cstdlib>
#include <future>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>

#include "api/engines/engine_names.h"
#include "cli/commands.h"
#include "cli/store_choice.h"
#include "core/base/mutex.h"
#include "core/engines/product_pipeline.h"
#include "server/orbit_server.h"

namespace orbit::cli {
namespace {

// What the signal thread and the thread that runs the server share.
struct SignalState {
  Mutex mutex;
  server::OrbitServer* server ABSL_GUARDED_BY(mutex) = nullptr;  // set once it serves
  bool reload_when_serving ABSL_GUARDED_BY(mutex) = false;       // a SIGHUP while it loaded
  std::promise<int> stop;  // the signal that stops a serving server, set once
};

// Takes SIGTERM, SIGINT and SIGHUP (blocked in every thread) for the process's life. A server
// that still loads its store has accepted no call (each is refused until the load ends) and its
// store's own writes at opening are transactions (docs/service.md, "Shutdown"), so SIGTERM or
// SIGINT then end the process at once, instead of after a load that takes tens of seconds on a
// large catalogue. Once it serves, they stop it cleanly, through `stop`; SIGHUP reloads the
// token file (once it serves, if sent before).
void TakeSignals(const sigset_t& signals, const std::shared_ptr<SignalState>& state) {
  for (;;) {
    int received = 0;
    if (sigwait(&signals, &received) != 0) continue;
    MutexLock lock(&state->mutex);
    if (received == SIGHUP) {
      if (state->server != nullptr) {
        std::cerr << "orbit serve: SIGHUP: reloading the token file" << std::endl;
        state->server->ReloadCredentials();
      } else {
        std::cerr << "orbit serve: SIGHUP while loading: the token file is read again once "
                     "the server serves"
                  << std::endl;
        state->reload_when_serving = true;
      }
      continue;
    }
    const char* name = received == SIGTERM ? "SIGTERM" : "SIGINT";
    if (state->server == nullptr) {
      std::cerr << "orbit serve: " << name << " while loading the store: stopped before serving"
                << std::endl;
      std::_Exit(0);
    }
    state->stop.set_value(received);
    return;
  }
}

struct ServeOptions {
  server::ServerConfig config;
  std::string database;
  std::string tokens, tls_cert, tls_key, tls_client_ca;
  std::string variant;  // "": the store's objects', the product's for an empty store
  std::string index = "kdtree";
  std::string engine{Product().engine};
  std::string rejection{RejectionRuleName(Product().options.rejection)};
};

int RunServe(ServeOptions& o) {
  server::ServerConfig& config = o.config;
  RequireOneStore("serve", o.database, config.store);
  config.database = o.database;
  if (!o.tokens.empty()) config.tokens_file = o.tokens;
  if (!o.tls_cert.empty()) config.tls_cert = o.tls_cert;
  if (!o.tls_key.empty()) config.tls_key = o.tls_key;
  if (!o.tls_client_ca.empty()) config.tls_client_ca = o.tls_client_ca;
  if (!o.variant.empty()) config.variant = *ParseVariant(o.variant);
  config.index.search = o.index == "exact" ? SearchMode::kExact : SearchMode::kKdTree;
  config.session_defaults.engine = ParseSessionEngine(o.engine);
  config.session_defaults.options.rejection = ParseRejectionRule(o.rejection);
  server::ValidateServerConfig(config);  // before the account below claims it will run

  // SIGTERM and SIGINT are taken by sigwait below: block them before any server thread exists,
  // so that every thread inherits the mask.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGHUP);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  auto signal_state = std::make_shared<SignalState>();
  std::future<int> stop = signal_state->stop.get_future();
  std::thread(TakeSignals, signals, signal_state).detach();

  std::cerr << config.Describe();
  std::cerr << "orbit serve: loading the store (SIGTERM or SIGINT stops the start)" << std::endl;
  server::OrbitServer server(config);
  if (!server.metrics_address().empty()) {
    std::cerr << "orbit serve: metrics on http://" << server.metrics_address() << "/metrics"
              << std::endl;
  }
  std::cerr << "orbit serve: descriptor variant " << VariantName(server.variant())
            << (o.variant.empty() ? " (not given: the store's, or the product's for a new store)"
                                  : "")
            << std::endl;
  std::cerr << "orbit serve: listening on " << server.address() << std::endl;

  {
    MutexLock lock(&signal_state->mutex);
    signal_state->server = &server;
    if (signal_state->reload_when_serving) server.ReloadCredentials();
  }
  const int received = stop.get();
  std::cerr << "orbit serve: " << (received == SIGTERM ? "SIGTERM" : "SIGINT")
            << ": shutting down (up to " << config.shutdown_grace_seconds << " s)" << std::endl;
  server.Shutdown();
  std::cerr << "orbit serve: stopped" << std::endl;
  return 0;
}

void ConnectionLimitsFlags(CLI::App& cmd, server::ConnectionLimits& c) {
  cmd.add_option("--handshake-timeout", c.handshake_timeout_seconds,
                 "seconds a new connection has to finish TLS and send its HTTP/2 settings")
      ->capture_default_str();
  cmd.add_option("--connection-idle-timeout", c.idle_timeout_seconds,
                 "seconds a connection may stay open with no call before it is closed (a\n"
                 "client reconnects at its next call; sessions are calls, never idle)")
      ->capture_default_str();
  cmd.add_option("--connection-max-age", c.max_age_seconds,
                 "seconds after which a connection is asked to reconnect, so that clients\n"
                 "spread over a balancer's servers (0: never)")
      ->capture_default_str();
  cmd.add_option("--connection-age-grace", c.age_grace_seconds,
                 "seconds the calls of a connection past --connection-max-age get to end")
      ->capture_default_str();
  cmd.add_option("--keepalive", c.keepalive_seconds,
                 "seconds of quiet after which the server pings a connection")
      ->capture_default_str();
  cmd.add_option("--keepalive-timeout", c.keepalive_timeout_seconds,
                 "seconds a ping's answer may take before the connection is closed")
      ->capture_default_str();
  cmd.add_option("--max-streams-per-connection", c.max_streams_per_connection,
                 "calls open at once on one connection")
      ->capture_default_str();
  cmd.add_option("--connection-memory", c.memory_mib,
                 "MiB gRPC's buffers of all connections may hold; above it new connections\n"
                 "are dropped")
      ->capture_default_str();
  cmd.add_option("--descriptor-reserve", c.descriptor_reserve,
                 "file descriptors kept free for the store and the logs: a connection that\n"
                 "would use one is closed at once (the descriptor limit itself is ulimit -n,\n"
                 "raised to its hard limit at start)")
      ->capture_default_str();
}

}  // namespace

void AddServeCommand(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ServeOptions>();
  server::ServerConfig& c = o->config;
  CLI::App* cmd = app.add_subcommand(
      "serve",
      "Run the recognition server (gRPC) on an embedded SQLite model store (--db), or on a\n"
      "PostgreSQL one that replicas share (--store), until SIGTERM or SIGINT (SIGHUP reloads\n"
      "the token file). Every option\n"
      "can also come from the environment (ORBIT_...) or from a config file (--config FILE,\n"
      "`option = value` lines). Without --tokens the server accepts anyone, so it listens on\n"
      "loopback only unless --allow-remote-without-tokens is given.");
  cmd->set_config("--config", "", "read options from this TOML/INI file");
  cmd->add_option("--db", o->database, "the model store (SQLite file; created when missing)")
      ->envname("ORBIT_DB");
  cmd->add_option("--store", c.store,
                  "a PostgreSQL model store instead of --db, which several servers may share:\n"
                  "a libpq connection string, postgresql://USER:PASSWORD@HOST:PORT/DBNAME or\n"
                  "\"host=... dbname=...\" (tables created in an empty schema; docs/storage.md)")
      ->envname("ORBIT_STORE");
  cmd->add_option("--store-grace", c.store_grace_seconds,
                  "with --store: seconds the server may lose the PostgreSQL store before its\n"
                  "health reports NOT_SERVING (a balancer then sends new sessions elsewhere)")
      ->check(CLI::Range(0, 86400))
      ->capture_default_str()
      ->envname("ORBIT_STORE_GRACE");
  cmd->add_option("--listen", c.listen, "HOST:PORT to serve on (port 0: any free port)")
      ->capture_default_str()
      ->envname("ORBIT_LISTEN");
  cmd->add_option("--tokens", o->tokens,
                  "token file: lines `<name> recognize|admin <sha256>` as `orbit token` prints\n"
                  "them (`<token> <role>` still read, with a warning); mode 600. Clients send\n"
                  "`authorization: Bearer <token>`. Read again on SIGHUP or when it changes")
      ->check(CLI::ExistingFile)
      ->envname("ORBIT_TOKENS");
  cmd->add_option("--tls-cert", o->tls_cert, "PEM certificate chain: serve TLS (with --tls-key)")
      ->check(CLI::ExistingFile)
      ->envname("ORBIT_TLS_CERT");
  cmd->add_option("--tls-key", o->tls_key, "PEM private key of --tls-cert")
      ->check(CLI::ExistingFile)
      ->envname("ORBIT_TLS_KEY");
  cmd->add_option("--tls-client-ca", o->tls_client_ca,
                  "PEM CA bundle: mutual TLS, every client must show a certificate it signed;\n"
                  "token-file lines `<name> <role> certificate` grant a role to the certificate\n"
                  "whose common name is <name>. Certificate, key and CA files are watched:\n"
                  "renewed ones are served within 5 s")
      ->check(CLI::ExistingFile)
      ->envname("ORBIT_TLS_CLIENT_CA");
  cmd->add_option("--audit-log", c.audit_log,
                  "where every enrollment, added view and deletion, and every refused token, is\n"
                  "recorded (a JSON line each): a file (appended, mode 600) or - for stderr")
      ->capture_default_str()
      ->envname("ORBIT_AUDIT_LOG");
  cmd->add_flag("--allow-remote-without-tokens", c.allow_remote_without_tokens,
                "serve a non-loopback address with no access control (unsafe)");
  cmd->add_option("--variant", o->variant,
                  "descriptor variant of the models and sessions (default: that of the objects "
                  "in the store; for a new store " +
                      std::string(VariantName(Product().variant)) +
                      ", the product pipeline: " + DescribeProduct() + ")")
      ->check(CLI::IsMember(VariantNames()))
      ->envname("ORBIT_VARIANT");
  cmd->add_option("--index", o->index, "view search: kdtree (FLANN) or exact (brute force)")
      ->check(CLI::IsMember({"kdtree", "exact"}))
      ->capture_default_str();
  cmd->add_option("--engine", o->engine,
                  "default engine of sessions that do not choose one (the product pipeline's: "
                  "docs/results/robustness.md)")
      ->check(CLI::IsMember(SessionEngineNames()))
      ->capture_default_str();
  cmd->add_option("--window", c.session_defaults.options.window, "default window W")
      ->check(CLI::Range(1, kMaxWindow))
      ->capture_default_str();
  cmd->add_option("--candidates-above", c.candidates_above,
                  "sessions' HMM scores only the " + std::to_string(kProductCandidateObjects) +
                      " objects per frame whose sector summaries the index finds most like it "
                      "once the model set holds more than this many objects, and every object "
                      "below (default: " +
                      std::to_string(kProductCandidatesAbove) +
                      " for a variant with appearance channels, " +
                      std::to_string(kCeddCandidatesAbove) +
                      " for the CEDD-only ones, where each costs less; "
                      "docs/design.md#object-candidates)")
      ->check(CLI::Range(0, kMaxCandidatesAbove));
  cmd->add_option("--rejection", o->rejection,
                  "default accept / unknown rule: calibrated (the product's: a threshold from "
                  "--false-accept-rate, computed from the model set) or th (the thesis' rule in "
                  "docs/design.md, --threshold)")
      ->check(CLI::IsMember({"calibrated", "th"}))
      ->capture_default_str();
  cmd->add_option("--false-accept-rate", c.false_accept_rate,
                  "the calibrated rule's target share of unknown objects accepted, in (0, 1) "
                  "(default: the variant's, " +
                      DescribeProductFalseAcceptRates() +
                      "; measured in docs/results/recognition.md and real-objects.md)")
      ->check(CLI::Range(1e-6, 1 - 1e-6));
  cmd->add_option("--known-accept-rate", c.session_defaults.options.known_accept_rate,
                  "the share of the known objects' own simulated windows the calibrated rule "
                  "raises its threshold to accept where look-alikes need more, within a bound "
                  "(docs/design.md#known-share), in [0, 1); 0: the target rate alone")
      ->check(CLI::Range(0.0, 1 - 1e-6))
      ->capture_default_str();
  cmd->add_option("--threshold", c.session_defaults.options.threshold, "Th of the th rule")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--max-sessions", c.limits.max_sessions, "concurrent sessions")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str()
      ->envname("ORBIT_MAX_SESSIONS");
  cmd->add_option("--max-fps", c.limits.max_frames_per_second, "frames per second per session")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--max-window", c.limits.max_window, "largest window a session may ask for")
      ->check(CLI::Range(1, kMaxWindow))
      ->capture_default_str();
  cmd->add_option("--max-hmm-cells", c.limits.max_hmm_cells,
                  "largest window x HMM states a session may ask for (about 10 bytes per cell "
                  "and enrolled object)")
      ->check(CLI::Range(1, kMaxWindow * kMaxHmmStates))
      ->capture_default_str();
  cmd->add_option("--max-message-bytes", c.limits.max_message_bytes, "largest request message")
      ->check(CLI::Range(1024, 64 << 20))
      ->capture_default_str();
  cmd->add_option("--max-image-pixels", c.limits.max_image_pixels,
                  "largest width x height of an uploaded image, read from its header before "
                  "decoding (PNG or JPEG; a decoded image takes up to 8 bytes a pixel)")
      ->check(CLI::Range(1, 1 << 30))
      ->capture_default_str();
  cmd->add_option("--max-queued-calls", c.limits.max_queued_calls,
                  "unary calls (Recognize, list, get, delete, add views) that may wait for a\n"
                  "worker, per pool; beyond it a call is refused with RESOURCE_EXHAUSTED")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_option("--max-sessions-per-token", c.limits.max_sessions_per_token,
                  "sessions one token may hold at once, with --tokens (0: no such limit); give\n"
                  "each device or fleet a token of its own")
      ->check(CLI::Range(0, 100000))
      ->capture_default_str();
  cmd->add_option("--max-recognize-calls-per-token", c.limits.max_recognize_calls_per_token,
                  "Recognize calls one token may have in progress at once, with --tokens (0: no\n"
                  "such limit)")
      ->check(CLI::Range(0, 100000))
      ->capture_default_str();
  cmd->add_option("--max-enrollments", c.limits.max_enrollments, "Enroll streams open at once")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  cmd->add_option("--max-enrollment-bytes", c.limits.max_enrollment_bytes,
                  "bytes of one Enroll stream's views together (held until the stream ends)")
      ->check(CLI::Range(std::int64_t{1} << 10, std::int64_t{16} << 30))
      ->capture_default_str();
  cmd->add_option("--enrollment-idle-timeout", c.limits.enrollment_idle_timeout_seconds,
                  "seconds an Enroll stream may go without a message before it is cancelled")
      ->check(CLI::Range(1, 86400))
      ->capture_default_str();
  cmd->add_option("--idle-timeout", c.limits.idle_timeout_seconds,
                  "seconds without a frame before a session is closed")
      ->check(CLI::Range(1, 86400))
      ->capture_default_str();
  // Connection limits: their ranges are checked once, by ValidateConnectionLimits.
  ConnectionLimitsFlags(*cmd, c.connections);
  cmd->add_option("--bulk-workers", c.bulk_worker_threads,
                  "worker threads for image frames and enrollments, apart from the descriptor\n"
                  "frames of every session (0: half the cores, at least one)")
      ->check(CLI::Range(0, 1024))
      ->capture_default_str();
  cmd->add_option("--workers", c.worker_threads,
                  "worker threads for unary calls (Recognize, list, get, delete);\n"
                  "a session's descriptor frames run on gRPC's threads (0: one per core)")
      ->check(CLI::Range(0, 1024))
      ->capture_default_str();
  cmd->add_option("--metrics-listen", c.metrics_listen,
                  "HOST:PORT to serve Prometheus metrics on, at http://HOST:PORT/metrics\n"
                  "(IPv4 address or host name; port 0: any free port). No TLS and no tokens:\n"
                  "use loopback or a management network. Off when not given")
      ->envname("ORBIT_METRICS_LISTEN");
  cmd->add_option("--shutdown-grace", c.shutdown_grace_seconds,
                  "seconds open calls get to finish on SIGTERM")
      ->check(CLI::Range(0, 600))
      ->capture_default_str();
  cmd->callback([o, &exit_code] { exit_code = RunServe(*o); });
}

}  // namespace orbit::cli
