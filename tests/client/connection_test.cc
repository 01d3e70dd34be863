// Connections (client/connection.h): unreachable and silent servers fail within the deadline
// with the right code; tokens and TLS reach a real `orbit serve` process; connections share a
// TCP connection unless asked to open their own.
#include "client/connection.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <grpcpp/generic/async_generic_service.h>
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include "client/models_client.h"
#include "client/recognition_session.h"
#include "client/rpc_error.h"
#include "tests/support/client_test_support.h"
#include "tests/support/server_process.h"

namespace orbit {
namespace {

using testing::CoilImage;
using testing::EnrollCoilObjects;
using testing::RpcCodeOf;
using testing::ServerProcess;

// A free loopback port with nothing listening on it.
std::string RefusedAddress() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address);
  socklen_t length = sizeof address;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length);
  ::close(fd);
  return "127.0.0.1:" + std::to_string(ntohs(address.sin_port));
}

// A gRPC server that accepts every call and never answers any: its calls stay queued for a
// generic service that never asks for them.
class SilentServer {
 public:
  SilentServer() {
    grpc::ServerBuilder builder;
    builder.AddListeningPort("127.0.0.1:0", grpc::InsecureServerCredentials(), &port_);
    builder.RegisterAsyncGenericService(&service_);
    queue_ = builder.AddCompletionQueue();
    server_ = builder.BuildAndStart();
  }
  ~SilentServer() {
    server_->Shutdown(std::chrono::system_clock::now());
    queue_->Shutdown();
    void* tag = nullptr;
    bool ok = false;
    while (queue_->Next(&tag, &ok)) {
    }
  }
  std::string address() const { return "127.0.0.1:" + std::to_string(port_); }

 private:
  int port_ = 0;
  grpc::AsyncGenericService service_;
  std::unique_ptr<grpc::ServerCompletionQueue> queue_;
  std::unique_ptr<grpc::Server> server_;
};

// A TCP relay on a free loopback port to a local `target_port` that holds each connection for
// `delay` before relaying it: what a slow link's round trips do to a connection's handshake.
class SlowLink {
 public:
  SlowLink(int target_port, std::chrono::milliseconds delay)
      : target_port_(target_port), delay_(delay) {
    listener_ = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address = Loopback(0);
    ::bind(listener_, reinterpret_cast<sockaddr*>(&address), sizeof address);
    ::listen(listener_, 8);
    socklen_t length = sizeof address;
    ::getsockname(listener_, reinterpret_cast<sockaddr*>(&address), &length);
    port_ = ntohs(address.sin_port);
    threads_.emplace_back([this] { AcceptAll(); });
  }
  ~SlowLink() {
    stopping_ = true;
    ::shutdown(listener_, SHUT_RDWR);  // wakes accept()
    {
      std::lock_guard lock(mutex_);
      for (const int fd : sockets_) ::shutdown(fd, SHUT_RDWR);  // wakes the relays' read()
    }
    for (;;) {  // relays may still be starting threads of their own: join until none is left
      std::vector<std::thread> threads;
      {
        std::lock_guard lock(mutex_);
        threads.swap(threads_);
      }
      if (threads.empty()) break;
      for (std::thread& t : threads) t.join();
    }
    for (const int fd : sockets_) ::close(fd);
    ::close(listener_);
  }
  std::string address() const { return "127.0.0.1:" + std::to_string(port_); }

 private:
  static sockaddr_in Loopback(int port) {
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    address.sin_port = htons(static_cast<std::uint16_t>(port));
    return address;
  }

  void AcceptAll() {
    for (;;) {
      const int client = ::accept(listener_, nullptr, nullptr);
      if (client < 0 || stopping_) {
        if (client >= 0) ::close(client);
        return;
      }
      std::lock_guard lock(mutex_);
      sockets_.push_back(client);
      threads_.emplace_back([this, client] { Relay(client); });
    }
  }

  void Relay(int client) {
    std::this_thread::sleep_for(delay_);
    const int server = ::socket(AF_INET, SOCK_STREAM, 0);
    {
      // Connected under the lock, so that the destructor's shutdown finds it connected.
      std::lock_guard lock(mutex_);
      sockets_.push_back(server);
      if (stopping_) return;
      const sockaddr_in address = Loopback(target_port_);
      if (::connect(server, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
        ::shutdown(client, SHUT_RDWR);
        return;
      }
    }
    std::thread back([client, server] { Pump(server, client); });
    Pump(client, server);
    back.join();
  }

  // Copies `from` to `to` until `from` ends, then ends `to`'s direction. A peer that closed
  // first ends the copy (send's MSG_NOSIGNAL: no SIGPIPE, which would kill the test binary).
  static void Pump(int from, int to) {
    char buffer[16384];
    for (;;) {
      const ssize_t n = ::read(from, buffer, sizeof buffer);
      if (n <= 0) break;
      for (ssize_t done = 0; done < n;) {
        const ssize_t w =
            ::send(to, buffer + done, static_cast<std::size_t>(n - done), MSG_NOSIGNAL);
        if (w <= 0) return;
        done += w;
      }
    }
    ::shutdown(to, SHUT_WR);
  }

  const int target_port_;
  const std::chrono::milliseconds delay_;
  int listener_ = -1;
  int port_ = 0;
  std::atomic<bool> stopping_{false};
  std::mutex mutex_;
  std::vector<int> sockets_;
  std::vector<std::thread> threads_;
};

TEST(ConnectionTest, UnreachableAndSilentServersFailWithinTheDeadline) {
  const Connection nobody(testing::At(RefusedAddress(), std::chrono::milliseconds(2000)));
  EXPECT_EQ(RpcCodeOf([&] { ModelsClient(nobody).ServerInfo(); }), grpc::StatusCode::UNAVAILABLE);
  EXPECT_EQ(RpcCodeOf([&] { RecognitionSession::Open(nobody, {}); }),
            grpc::StatusCode::UNAVAILABLE);

  // A server that never answers: the call ends at its deadline.
  const SilentServer silent;
  const Connection mute(testing::At(silent.address(), std::chrono::milliseconds(300)));
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(RpcCodeOf([&] { ModelsClient(mute).ServerInfo(); }),
            grpc::StatusCode::DEADLINE_EXCEEDED);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));

  try {
    ModelsClient(nobody).ServerInfo();
    FAIL() << "no error";
  } catch (const RpcError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("ServerInfo: UNAVAILABLE", 0), 0u) << e.what();
  }
}

TEST(ConnectionTest, TokensAndTlsReachTheServer) {
  const testing::ScratchDir scratch;
  const std::filesystem::path& dir = scratch.path();
  ServerProcess server(
      testing::SecuredServerOptions(dir, "orbit.test", "admin-secret-0001", "reader-secret-0001"));
  ConnectionOptions tls = testing::At(server.address());
  tls.tls_root_certificates_file = (dir / "cert.pem").string();
  tls.tls_server_name = "orbit.test";

  ConnectionOptions admin = tls;
  admin.token = "admin-secret-0001";
  const Connection admin_connection(admin);
  EnrollCoilObjects(admin_connection, 1, 1);

  ConnectionOptions reader = tls;
  reader.token = ReadTokenFile((dir / "reader.token").string());
  EXPECT_EQ(reader.token, "reader-secret-0001");
  const Connection reader_connection(reader);
  EXPECT_EQ(ModelsClient(reader_connection).ServerInfo().object_count(), 1);
  EXPECT_EQ(RpcCodeOf([&] { ModelsClient(reader_connection).DeleteObject(ObjectByName("obj1")); }),
            grpc::StatusCode::PERMISSION_DENIED);
  auto session = RecognitionSession::Open(reader_connection, {});
  session->Push(CoilImage(1, 15), 15);
  const std::optional<v1::SessionUpdate> update = session->NextUpdate();
  ASSERT_TRUE(update.has_value());
  ASSERT_GT(update->candidates_size(), 0);
  EXPECT_EQ(update->candidates(0).name(), "obj1");
  EXPECT_TRUE(session->Close().ok());

  const Connection anonymous(tls);
  EXPECT_EQ(RpcCodeOf([&] { ModelsClient(anonymous).ServerInfo(); }),
            grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_EQ(RpcCodeOf([&] { RecognitionSession::Open(anonymous, {}); }),
            grpc::StatusCode::UNAUTHENTICATED);
  ConnectionOptions plaintext = admin;
  plaintext.tls_root_certificates_file.clear();
  EXPECT_EQ(RpcCodeOf([&] { ModelsClient(Connection(plaintext)).ServerInfo(); }),
            grpc::StatusCode::UNAVAILABLE);
}

// A connection whose handshake takes a few hundred milliseconds, as over a phone's mobile link
// (or to a busy server), is made: the call waits for it within its deadline. (The client once
// gave every connection attempt 100 ms, and such a first call failed at once with UNAVAILABLE:
// "connection attempt timed out before receiving SETTINGS frame".)
TEST(ConnectionTest, ASlowHandshakeStillConnects) {
  ServerProcess server;
  const SlowLink link(server.port(), std::chrono::milliseconds(400));
  const Connection connection(testing::At(link.address()));
  EXPECT_EQ(ModelsClient(connection).ServerInfo().object_count(), 0);
}

// Established TCP connections on this machine to port `port` (/proc/net/tcp and tcp6, as gRPC
// opens IPv6 sockets with IPv4-mapped addresses: the remote address's port in hex, state 01).
int EstablishedConnectionsTo(int port) {
  int count = 0;
  for (const char* file : {"/proc/net/tcp", "/proc/net/tcp6"}) {
    std::ifstream table(file);
    std::string line;
    std::getline(table, line);  // the header
    while (std::getline(table, line)) {
      std::istringstream fields(line);
      std::string slot, local, remote, state;
      fields >> slot >> local >> remote >> state;
      const std::size_t colon = remote.rfind(':');
      if (state == "01" && colon != std::string::npos &&
          std::stoi(remote.substr(colon + 1), nullptr, 16) == port) {
        ++count;
      }
    }
  }
  return count;
}

// gRPC shares one TCP connection among channels to the same address with the same options; a
// load generator standing for separate devices needs one each (orbit loadtest --connections).
TEST(ConnectionTest, OwnConnectionsOpenATcpConnectionEach) {
  ServerProcess server;
  const Connection shared_a(testing::At(server.address()));
  const Connection shared_b(testing::At(server.address()));
  ModelsClient(shared_a).ServerInfo();
  ModelsClient(shared_b).ServerInfo();
  EXPECT_EQ(EstablishedConnectionsTo(server.port()), 1);

  ConnectionOptions own = testing::At(server.address());
  own.own_connection = true;
  const Connection own_a(own);
  const Connection own_b(own);
  ModelsClient(own_a).ServerInfo();
  ModelsClient(own_b).ServerInfo();
  EXPECT_EQ(EstablishedConnectionsTo(server.port()), 3);
}

}  // namespace
}  // namespace orbit
