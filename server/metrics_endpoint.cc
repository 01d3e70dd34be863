#include "server/metrics_endpoint.h"

#include <civetweb.h>
#include <netdb.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <string_view>
#include <thread>

#include "server/metrics.h"

namespace orbit::server {
namespace {

constexpr const char* kContentType = "text/plain; version=0.0.4; charset=utf-8";

// Splits "HOST:PORT", checking what civetweb's listening_ports would read differently: a list
// (","), an IPv6 address ("[...]"), or a port with civetweb's suffixes ("9464s" serves TLS).
void SplitAddress(const std::string& host_and_port, std::string* host, std::string* port) {
  const auto colon = host_and_port.rfind(':');
  const std::string_view text = host_and_port;
  const bool ok = [&] {
    if (colon == std::string::npos || colon == 0) return false;
    const std::string_view h = text.substr(0, colon), p = text.substr(colon + 1);
    if (h.find_first_of(":[], \t") != std::string_view::npos) return false;
    if (p.empty() || p.size() > 5 || p.find_first_not_of("0123456789") != std::string_view::npos) {
      return false;
    }
    return std::stoi(std::string(p)) <= 65535;
  }();
  if (!ok) {
    throw std::invalid_argument("'" + host_and_port +
                                "' is not HOST:PORT with an IPv4 address or host name and a "
                                "port 0..65535 (IPv6 is not supported for metrics)");
  }
  *host = host_and_port.substr(0, colon);
  *port = host_and_port.substr(colon + 1);
}

// Opens and closes one TCP connection to host:port (0.0.0.0 reached through 127.0.0.1), to
// wake civetweb's listening thread; whether it connects does not matter.
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

void InitCivetwebOnce() {
  static std::once_flag once;
  std::call_once(once, [] { mg_init_library(0); });
}

}  // namespace

MetricsEndpoint::MetricsEndpoint(const std::string& host_and_port, const MetricsRegistry& registry)
    : host_(host_and_port.substr(0, host_and_port.rfind(':'))), registry_(registry) {
  std::string host, port;
  SplitAddress(host_and_port, &host, &port);
  InitCivetwebOnce();
  const std::string listening = host + ":" + port;
  const char* options[] = {"listening_ports", listening.c_str(),  //
                           "num_threads", "2",  // Prometheus scrapes one request at a time
                           "request_timeout_ms", "10000",  //
                           nullptr};
  mg_callbacks callbacks{};
  callbacks.log_message = &MetricsEndpoint::LogMessage;
  mg_init_data init{&callbacks, this, options};
  char error_text[256] = "";
  unsigned error_code = 0;
  mg_error_data error{&error_code, error_text, sizeof error_text};
  context_ = mg_start2(&init, &error);
  std::lock_guard lock(log_mutex_);
  started_ = true;
  if (context_ == nullptr) {
    // civetweb's log names the cause ("cannot bind to ...: 98 (Address already in use)") before
    // its summary ("Failed to setup server ports"); the first line is the useful one.
    const std::string cause =
        log_.empty() ? std::string(error_text) : log_.substr(0, log_.find('\n'));
    throw std::runtime_error(cause);
  }
  mg_server_port ports[1];
  if (mg_get_server_ports(context_, 1, ports) == 1) port_ = ports[0].port;
  mg_set_request_handler(context_, "/metrics$", &MetricsEndpoint::ServeMetrics, this);
}

MetricsEndpoint::~MetricsEndpoint() {
  if (context_ == nullptr) return;
  // mg_stop returns once civetweb's listening thread has seen the stop, which it looks for only
  // when its poll() returns: every 2 s, or as soon as a connection arrives. Knocking until the
  // stop is done makes it take milliseconds instead of up to 2 s (a server's shutdown waits
  // for it).
  std::atomic<bool> stopped = false;
  std::thread stopper([this, &stopped] {
    mg_stop(context_);
    stopped = true;
  });
  while (!stopped) {
    Knock(host_, port_);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  stopper.join();
}

std::string MetricsEndpoint::address() const { return host_ + ":" + std::to_string(port_); }

int MetricsEndpoint::LogMessage(const mg_connection* connection, const char* message) {
  const mg_context* context = connection != nullptr ? mg_get_context(connection) : nullptr;
  auto* endpoint =
      context != nullptr ? static_cast<MetricsEndpoint*>(mg_get_user_data(context)) : nullptr;
  if (endpoint != nullptr) {
    std::lock_guard lock(endpoint->log_mutex_);
    if (!endpoint->started_) endpoint->log_ += std::string(message) + "\n";
  }
  return 1;  // handled: civetweb prints nothing itself
}

int MetricsEndpoint::ServeMetrics(mg_connection* connection, void* endpoint) {
  const std::string_view method = mg_get_request_info(connection)->request_method;
  if (method != "GET" && method != "HEAD") {
    mg_printf(connection,
              "HTTP/1.1 405 Method Not Allowed\r\nAllow: GET, HEAD\r\nContent-Length: 0\r\n"
              "Connection: close\r\n\r\n");
    return 405;
  }
  std::string text;
  try {
    text = static_cast<const MetricsEndpoint*>(endpoint)->registry_.Expose();
  } catch (const std::exception& e) {
    mg_send_http_error(connection, 500, "%s", e.what());
    return 500;
  }
  mg_send_http_ok(connection, kContentType, static_cast<long long>(text.size()));
  if (method == "GET") mg_write(connection, text.data(), text.size());
  return 200;
}

}  // namespace orbit::server
