// MetricsEndpoint: a MetricsRegistry's text exposition served over HTTP at
// http://HOST:PORT/metrics, for Prometheus to scrape (`orbit serve --metrics-listen`).
//
// The HTTP server is civetweb (Debian's libcivetweb, the server prometheus-cpp's own exposer
// uses), with two threads: a scrape renders the registry's text on one of them and never touches
// gRPC's threads or the workers. Only GET and HEAD of /metrics are answered (other methods 405,
// other paths 404); there is no TLS and no access control, so the address should be loopback or
// a management network (docs/service.md, "Metrics").
//
// Thread-safe: immutable after construction.
#pragma once

#include <mutex>
#include <string>

struct mg_connection;
struct mg_context;

namespace orbit::server {

class MetricsRegistry;

class MetricsEndpoint {
 public:
  // Serves `registry` on `host_and_port`: an IPv4 address or a host name that resolves to one,
  // a colon, and a port (0: any free port), e.g. "127.0.0.1:9464" or "0.0.0.0:9464". Throws
  // std::invalid_argument when the address is not of that form (IPv6 included: Debian's civetweb
  // is built without it) and std::runtime_error when it cannot be bound (in use, not an address
  // of this machine), with the reason civetweb gives, e.g.
  // "cannot bind to 127.0.0.1:9464: 98 (Address already in use)". Serving once constructed.
  // `registry` must outlive the endpoint.
  MetricsEndpoint(const std::string& host_and_port, const MetricsRegistry& registry);
  // Stops listening; returns once no scrape is being answered.
  ~MetricsEndpoint();

  MetricsEndpoint(const MetricsEndpoint&) = delete;
  MetricsEndpoint& operator=(const MetricsEndpoint&) = delete;

  // The port bound (useful with port 0).
  int port() const { return port_; }
  // The address scrapers should use, HOST:PORT with the bound port.
  std::string address() const;

 private:
  // civetweb's callbacks.
  static int LogMessage(const mg_connection* connection, const char* message);
  static int ServeMetrics(mg_connection* connection, void* endpoint);

  const std::string host_;
  const MetricsRegistry& registry_;
  mg_context* context_ = nullptr;
  int port_ = 0;
  std::mutex log_mutex_;
  std::string log_;       // guarded by log_mutex_: what civetweb reported while starting
  bool started_ = false;  // guarded by log_mutex_: later reports are dropped
};

}  // namespace orbit::server
