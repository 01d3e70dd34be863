// MetricsEndpoint: the server's metrics served over HTTP at http://HOST:PORT/metrics for
// Prometheus to scrape (`orbit serve --metrics-listen`), by prometheus-cpp's Exposer.
//
// The exposer runs its own HTTP server (civetweb) with two threads: a scrape collects the
// metrics on one of them and never touches gRPC's threads or the workers. There is no TLS and no
// access control, so the address should be loopback or a management network (docs/service.md,
// "Metrics").
//
// Thread-safe: immutable after construction.
#pragma once

#include <memory>
#include <string>

namespace prometheus {
class Exposer;
}

namespace orbit::server {

class ServerMetrics;

class MetricsEndpoint {
 public:
  // Serves `metrics` on `host_and_port`: an IPv4 address or a host name that resolves to one, a
  // colon, and a port (0: any free port), e.g. "127.0.0.1:9464" or "0.0.0.0:9464". Throws
  // std::invalid_argument when the address is not of that form (IPv6 included: Debian's civetweb
  // is built without it) and std::runtime_error when it cannot be bound (in use, not an address
  // of this machine). Serving once constructed. `metrics` must outlive the endpoint.
  MetricsEndpoint(const std::string& host_and_port, const ServerMetrics& metrics);
  // Stops listening; returns once no scrape is being answered.
  ~MetricsEndpoint();

  MetricsEndpoint(const MetricsEndpoint&) = delete;
  MetricsEndpoint& operator=(const MetricsEndpoint&) = delete;

  // The port bound (useful with port 0).
  int port() const { return port_; }
  // The address scrapers should use, HOST:PORT with the bound port.
  std::string address() const { return host_ + ":" + std::to_string(port_); }

 private:
  std::string host_;
  std::unique_ptr<prometheus::Exposer> exposer_;
  int port_ = 0;
};

}  // namespace orbit::server
