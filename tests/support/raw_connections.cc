#include "tests/support/raw_connections.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>

namespace orbit::testing {
namespace {

// The HTTP/2 client connection preface (RFC 9113, 3.4) and a SETTINGS frame with no settings
// (length 0, type 4, flags 0, stream 0).
constexpr char kPrefaceSettings[] =
    "PRI * HTTP/2.0\r\n\r\nSM\r\n\r\n"
    "\x00\x00\x00\x04\x00\x00\x00\x00\x00";
constexpr std::size_t kPrefaceSettingsBytes = sizeof kPrefaceSettings - 1;

}  // namespace

RawConnections::RawConnections(int port, int count, RawGreeting greeting) {
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  for (int i = 0; i < count; ++i) {
    const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0) break;  // this process's own descriptors ran out
    if (::connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0 ||
        (greeting == RawGreeting::kPrefaceSettings &&
         ::send(fd, kPrefaceSettings, kPrefaceSettingsBytes, MSG_NOSIGNAL) !=
             static_cast<ssize_t>(kPrefaceSettingsBytes))) {
      ::close(fd);
      continue;
    }
    sockets_.push_back(fd);
  }
}

int RawConnections::ClosedByServerWithin(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  std::vector<bool> closed(sockets_.size(), false);
  int count = 0;
  while (count < connected()) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) break;
    std::vector<pollfd> open;
    for (std::size_t i = 0; i < sockets_.size(); ++i) {
      if (!closed[i]) open.push_back({sockets_[i], POLLIN, 0});
    }
    if (::poll(open.data(), open.size(), static_cast<int>(std::min<long>(left.count(), 200))) <=
        0) {
      continue;
    }
    for (const pollfd& p : open) {
      if (p.revents == 0) continue;
      char buffer[4096];
      const ssize_t n = ::recv(p.fd, buffer, sizeof buffer, MSG_DONTWAIT);
      if (n > 0) continue;  // the server's frames; the close comes after
      const auto at = std::find(sockets_.begin(), sockets_.end(), p.fd) - sockets_.begin();
      closed[at] = true;
      ++count;
    }
  }
  return count;
}

void RawConnections::Close() {
  for (const int fd : sockets_) ::close(fd);
  sockets_.clear();
}

}  // namespace orbit::testing
