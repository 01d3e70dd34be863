// A minimal HTTP/1.0 client over a TCP socket, for the tests of the metrics endpoint: one request,
// the whole response read until the server closes the connection. Only what the tests need:
// no redirects, no chunked bodies, no TLS.
#pragma once

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <cctype>
#include <map>
#include <stdexcept>
#include <string>

namespace orbit::testing {

struct HttpResponse {
  int status = 0;                              // e.g. 200
  std::map<std::string, std::string> headers;  // names lower-cased
  std::string body;
};

// Sends `method path HTTP/1.0` to `address` ("127.0.0.1:PORT") and returns the response. Throws
// std::runtime_error when the connection fails or the response is not HTTP; waits at most 10 s.
inline HttpResponse HttpRequest(const std::string& address, const std::string& method,
                                const std::string& path) {
  const auto colon = address.rfind(':');
  sockaddr_in server{};
  server.sin_family = AF_INET;
  server.sin_port = htons(static_cast<std::uint16_t>(std::stoi(address.substr(colon + 1))));
  if (inet_pton(AF_INET, address.substr(0, colon).c_str(), &server.sin_addr) != 1) {
    throw std::runtime_error("not an IPv4 address: " + address);
  }
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) throw std::runtime_error("socket() failed");
  timeval timeout{10, 0};
  setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &timeout, sizeof timeout);
  std::string raw;
  try {
    if (connect(fd, reinterpret_cast<const sockaddr*>(&server), sizeof server) != 0) {
      throw std::runtime_error("cannot connect to " + address);
    }
    const std::string request = method + " " + path + " HTTP/1.0\r\nHost: " + address + "\r\n\r\n";
    if (send(fd, request.data(), request.size(), MSG_NOSIGNAL) !=
        static_cast<ssize_t>(request.size())) {
      throw std::runtime_error("cannot send to " + address);
    }
    char buffer[4096];
    for (;;) {
      const ssize_t n = recv(fd, buffer, sizeof buffer, 0);
      if (n < 0) throw std::runtime_error("no response from " + address);
      if (n == 0) break;
      raw.append(buffer, static_cast<std::size_t>(n));
    }
  } catch (...) {
    close(fd);
    throw;
  }
  close(fd);

  HttpResponse response;
  const auto head_end = raw.find("\r\n\r\n");
  if (raw.rfind("HTTP/1.", 0) != 0 || head_end == std::string::npos) {
    throw std::runtime_error("not an HTTP response: " + raw.substr(0, 100));
  }
  response.status = std::stoi(raw.substr(raw.find(' ') + 1, 3));
  std::size_t line = raw.find("\r\n") + 2;
  while (line < head_end) {
    const std::size_t end = raw.find("\r\n", line);
    const std::string header = raw.substr(line, end - line);
    const auto separator = header.find(':');
    std::string name = header.substr(0, separator);
    for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const auto value = header.find_first_not_of(' ', separator + 1);
    response.headers[name] = value == std::string::npos ? "" : header.substr(value);
    line = end + 2;
  }
  response.body = raw.substr(head_end + 4);
  return response;
}

}  // namespace orbit::testing
