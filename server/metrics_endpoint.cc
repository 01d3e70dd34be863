#include "server/metrics_endpoint.h"

#include <netdb.h>
#include <prometheus/exposer.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <string_view>
#include <thread>

#include "server/server_metrics.h"

namespace orbit::server {
namespace {

// Checks "HOST:PORT" for what civetweb's listening_ports would read differently: a list (","),
// an IPv6 address ("[...]"), or a port with civetweb's suffixes ("9464s" serves TLS).
void CheckAddress(const std::string& host_and_port) {
  const auto colon = host_and_port.rfind(':');
  const std::string_view text = host_and_port;
  const bool ok = [&] {
    if (colon == std::string::npos || colon == 0) return false;
    const std::string_view host = text.substr(0, colon), port = text.substr(colon + 1);
    if (host.find_first_of(":[], \t") != std::string_view::npos) return false;
    if (port.empty() || port.size() > 5 ||
        port.find_first_not_of("0123456789") != std::string_view::npos) {
      return false;
    }
    return std::stoi(std::string(port)) <= 65535;
  }();
  if (!ok) {
    throw std::invalid_argument("'" + host_and_port +
                                "' is not HOST:PORT with an IPv4 address or host name and a "
                                "port 0..65535 (IPv6 is not supported for metrics)");
  }
}

// Opens and closes one TCP connection to host:port (0.0.0.0 reached through 127.0.0.1), to wake
// civetweb's listening thread; whether it connects does not matter.
void Knock(const std::string& host, int port) {
  addrinfo hints{};
  hints.ai_family = AF_INET;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* found = nullptr;
  const std::string target = host == "0.0.0.0" ? "127.0.0.1" : host;
  if (getaddrinfo(target.c_str(), std::to_string(port).c_str(), &hints, &found) != 0) return;
  const int fd = socket(found->ai_family, found->ai_socktype, found->ai_protocol);
  if (fd >= 0) {
    connect(fd, found->ai_addr, found->ai_addrlen);
    close(fd);
  }
  freeaddrinfo(found);
}

}  // namespace

MetricsEndpoint::MetricsEndpoint(const std::string& host_and_port, const ServerMetrics& metrics)
    : host_(host_and_port.substr(0, host_and_port.rfind(':'))) {
  CheckAddress(host_and_port);
  try {
    // Two threads: Prometheus scrapes one request at a time, and a second keeps a slow client
    // from blocking it.
    exposer_ = std::make_unique<prometheus::Exposer>(host_and_port, 2);
  } catch (const std::exception&) {
    // civetweb says only "null context when constructing CivetServer".
    throw std::runtime_error("cannot listen on " + host_and_port +
                             " (address in use, or not an address of this machine?)");
  }
  for (const auto& collectable : metrics.collectables()) exposer_->RegisterCollectable(collectable);
  const std::vector<int> ports = exposer_->GetListeningPorts();
  if (!ports.empty()) port_ = ports.front();
}

MetricsEndpoint::~MetricsEndpoint() {
  // civetweb's listening thread sees the stop only when its poll() returns: every 2 s, or as
  // soon as a connection arrives. Knocking until the exposer is gone makes a server's shutdown
  // take milliseconds instead of up to 2 s.
  std::atomic<bool> stopped = false;
  std::thread stopper([this, &stopped] {
    exposer_.reset();
    stopped = true;
  });
  while (!stopped) {
    Knock(host_, port_);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  stopper.join();
}

}  // namespace orbit::server
