#include "server/server_config.h"

#include <arpa/inet.h>

#include <sstream>
#include <stdexcept>

#include "api/engines/engine_names.h"
#include "core/engines/product_pipeline.h"
#include "server/tls_credentials.h"
#include "storage/postgres_connection.h"

namespace orbit::server {

bool IsLoopbackAddress(const std::string& host_and_port) {
  std::string host = host_and_port;
  if (const auto colon = host.rfind(':'); colon != std::string::npos && host.front() != '[') {
    // "host:port"; a bare IPv6 address has several colons and no port here.
    if (host.find(':') == colon) host = host.substr(0, colon);
  } else if (host.front() == '[') {
    host = host.substr(1, host.find(']') - 1);
  }
  in_addr ipv4{};
  const bool ipv4_loopback =
      inet_pton(AF_INET, host.c_str(), &ipv4) == 1 && (ntohl(ipv4.s_addr) >> 24) == 127;
  return host == "localhost" || host == "::1" || ipv4_loopback;
}

void ValidateServerConfig(const ServerConfig& config) {
  if (grpc::Status s = CheckHmmCells(config.session_defaults, config.limits); !s.ok()) {
    const EngineOptions& o = config.session_defaults.options;
    throw std::invalid_argument("the default session (window " + std::to_string(o.window) + " x " +
                                std::to_string(o.hmm_states) +
                                " HMM states) is above --max-hmm-cells " +
                                std::to_string(config.limits.max_hmm_cells));
  }
  // The sessions' options as OrbitServer will run them, given threshold included.
  EngineOptions sessions = config.session_defaults.options;
  if (config.candidates_above) sessions.candidates_above = *config.candidates_above;
  if (config.false_accept_rate) sessions.false_accept_rate = *config.false_accept_rate;
  ValidateEngineOptions(sessions);
  ValidateConnectionLimits(config.connections);
  if (config.store_grace_seconds < 0) {
    throw std::invalid_argument("--store-grace " + std::to_string(config.store_grace_seconds) +
                                " is negative: give seconds, 0 or more");
  }
  if (!config.store.empty()) {
    try {
      RedactedTarget(config.store);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("--store: ") + e.what());
    }
  }
}

namespace {

// The model store as the start-up account names it: the password of a connection string never
// appears.
std::string DescribeStore(const ServerConfig& config) {
  if (config.store.empty()) return "SQLite " + config.database.string();
  try {
    return "PostgreSQL " + RedactedTarget(config.store);
  } catch (const std::invalid_argument&) {
    return "PostgreSQL (an invalid connection string)";
  }
}

std::string DescribeConnections(const ConnectionLimits& c) {
  std::ostringstream out;
  out << "handshake <= " << c.handshake_timeout_seconds << " s, closed after "
      << c.idle_timeout_seconds << " s without a call, ";
  if (c.max_age_seconds > 0) {
    out << "age <= " << c.max_age_seconds << " s (+" << c.age_grace_seconds << " s grace), ";
  }
  out << "pinged after " << c.keepalive_seconds << " s quiet (answer within "
      << c.keepalive_timeout_seconds << " s), " << c.max_streams_per_connection
      << " calls each, buffers <= " << c.memory_mib << " MiB, " << c.descriptor_reserve
      << " descriptors kept free";
  return out.str();
}

}  // namespace

std::string ServerConfig::Describe() const {
  const SessionSettings& d = session_defaults;
  std::ostringstream out;
  out << "orbit serve "
      << "configuration:\n"
      << "  model store         " << DescribeStore(*this) << "\n";
  if (!store.empty()) {
    out << "  store grace         " << store_grace_seconds
        << " s (then NOT_SERVING until the store answers)\n";
  }
  out << "  listen              " << listen << "\n"
      << "  access control      "
      << (tokens_file ? "tokens from " + tokens_file->string() : "none (loopback only)") << "\n"
      << "  audit log           " << (audit_log == "-" ? std::string("stderr") : audit_log) << "\n"
      << "  tls                 "
      << (tls_cert ? "certificate " + tls_cert->string() + ", key " + tls_key->string() +
                         (tls_client_ca ? ", client certificates of " + tls_client_ca->string()
                                        : std::string()) +
                         " (files watched: renewed ones served within " +
                         std::to_string(kCertificateRefreshSeconds) + " s)"
                   : "off")
      << "\n"
      << "  descriptor variant  "
      << (variant ? std::string(VariantName(*variant))
                  : "the store's objects' (" + std::string(VariantName(Product().variant)) +
                        " for an empty store)")
      << "\n"
      << "  index               "
      << (index.search == SearchMode::kKdTree
              ? "kd-tree (" + std::to_string(index.kd_trees) + " trees, " +
                    std::to_string(index.kd_checks) + " checks)"
              : std::string("exact"))
      << "\n"
      << "  session defaults    engine " << SessionEngineName(d.engine) << ", top-k "
      << d.options.top_k << ", window " << d.options.window << ", w "
      << d.options.orientation_weight << ", N_L " << d.options.list_length << ", HMM states "
      << d.options.hmm_states << ", HMM sharpness " << d.options.hmm_sharpness << ", rejection "
      << RejectionRuleName(d.options.rejection);
  if (d.options.rejection == RejectionRule::kCalibrated) {
    std::ostringstream rate;
    if (false_accept_rate) {
      rate << *false_accept_rate;
    } else if (variant) {
      rate << ProductFalseAcceptRate(*variant);
    } else {
      rate << "the variant's: " << DescribeProductFalseAcceptRates();
    }
    out << " (false-accept rate " << rate.str() << ", known-accept rate "
        << d.options.known_accept_rate << ")\n";
  } else {
    out << " (Th " << d.options.threshold << ")\n";
  }
  out << "  candidates          " << d.options.candidate_objects
      << " objects a frame, proposed by the index, above "
      << (candidates_above ? std::to_string(*candidates_above)
          : variant        ? std::to_string(ProductCandidatesAbove(*variant))
                           : "the variant's (" + std::to_string(kProductCandidatesAbove) +
                          " with appearance channels, " + std::to_string(kCeddCandidatesAbove) +
                          " without)")
      << " objects\n";
  out << "  limits              " << limits.max_sessions << " sessions, "
      << limits.max_frames_per_second << " frames/s per session, window <= " << limits.max_window
      << ", HMM window x states <= " << limits.max_hmm_cells
      << ", messages <= " << limits.max_message_bytes
      << " bytes, images <= " << limits.max_image_pixels << " pixels, idle "
      << limits.idle_timeout_seconds << " s, " << limits.max_queued_calls
      << " calls queued per pool, " << limits.max_sessions_per_token << " sessions and "
      << limits.max_recognize_calls_per_token << " Recognize calls per token, "
      << limits.max_enrollments << " enrollments of <= " << limits.max_enrollment_bytes
      << " bytes (idle " << limits.enrollment_idle_timeout_seconds << " s)\n"
      << "  connections         " << DescribeConnections(connections) << "\n"
      << "  workers             "
      << (worker_threads > 0 ? std::to_string(worker_threads) : "one per core")
      << ", for images and enrollments "
      << (bulk_worker_threads > 0 ? std::to_string(bulk_worker_threads) : "half the cores") << "\n"
      << "  shutdown grace      " << shutdown_grace_seconds << " s\n"
      << "  metrics             "
      << (metrics_listen.empty() ? std::string("off")
                                 : "http://" + metrics_listen + "/metrics (Prometheus)")
      << "\n";
  return out.str();
}

}  // namespace orbit::server
