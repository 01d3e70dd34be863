// Connections (client/connection.h): unreachable and silent servers fail within the deadline
// with the right code; tokens and TLS reach a real `orbit serve` process.
#include "client/connection.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>

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
  ServerProcess server(testing::SecuredServerOptions(dir, "orbit.test", "admin-secret-0001",
                                                     "reader-secret-0001"));
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

}  // namespace
}  // namespace orbit
