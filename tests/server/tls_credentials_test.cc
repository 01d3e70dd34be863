// The server's TLS (server/tls_credentials.h) against a real `orbit serve`: mutual TLS, where a
// client's certificate names its grant in the token file, and a certificate renewed on disk served
// without a restart. Certificates are made with openssl.
#include "server/tls_credentials.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include <grpcpp/grpcpp.h>

#include "orbit/v1/models.grpc.pb.h"
#include "server/token_file.h"
#include "tests/support/server_process.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

using testing::ServerProcess;

std::string Slurp(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void RunOpenssl(const std::string& command) {
  ASSERT_EQ(std::system((command + " 2>/dev/null").c_str()), 0) << command;
}

// dir/NAME.pem and dir/NAME.key: a certificate for CN=`name` signed by the CA in dir/ca.pem.
void MakeClientCertificate(const std::filesystem::path& dir, const std::string& name) {
  const std::string base = (dir / name).string();
  RunOpenssl("openssl req -newkey rsa:2048 -nodes -subj /CN=" + name + " -keyout " + base +
             ".key -out " + base + ".csr");
  RunOpenssl("openssl x509 -req -in " + base + ".csr -CA " + (dir / "ca.pem").string() +
             " -CAkey " + (dir / "ca.key").string() + " -CAcreateserial -days 2 -out " + base +
             ".pem");
}

// ListObjects over TLS trusting `server_cert`, showing the client certificate `client` (dir/
// client.pem and .key) unless empty, with `token` unless empty.
grpc::Status List(const std::string& address, const std::string& server_cert,
                  const std::filesystem::path& dir, const std::string& client,
                  const std::string& token = "") {
  grpc::SslCredentialsOptions ssl;
  ssl.pem_root_certs = server_cert;
  if (!client.empty()) {
    ssl.pem_private_key = Slurp(dir / (client + ".key"));
    ssl.pem_cert_chain = Slurp(dir / (client + ".pem"));
  }
  auto models = v1::Models::NewStub(grpc::CreateChannel(address, grpc::SslCredentials(ssl)));
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(5));
  if (!token.empty()) context.AddMetadata("authorization", "Bearer " + token);
  v1::ListObjectsResponse response;
  return models->ListObjects(&context, v1::ListObjectsRequest(), &response);
}

TEST(TlsCredentialsTest, MutualTlsGrantsAClientByItsCertificatesName) {
  testing::ScratchDir dir;
  testing::MakeSelfSignedCertificate(dir.path(), "localhost", "DNS:localhost");
  RunOpenssl("openssl req -x509 -newkey rsa:2048 -nodes -days 2 -subj /CN=orbit-test-ca -keyout " +
             (dir / "ca.key").string() + " -out " + (dir / "ca.pem").string());
  MakeClientCertificate(dir.path(), "device-7");
  MakeClientCertificate(dir.path(), "stranger");
  const std::string admin = "admin-token-0123456789";
  testing::WriteTokenFile(dir / "tokens",
                          "device-7 recognize certificate\n" +
                              server::TokenFileLine("ops", server::Role::kAdmin, admin) + "\n");
  ServerProcess server({.tokens_file = dir / "tokens",
                        .tls_cert = dir / "cert.pem",
                        .tls_key = dir / "key.pem",
                        .extra_args = {"--tls-client-ca", (dir / "ca.pem").string()}});
  const std::string address = "localhost:" + std::to_string(server.port());
  const std::string server_cert = Slurp(dir / "cert.pem");

  EXPECT_TRUE(List(address, server_cert, dir.path(), "device-7").ok())
      << "the certificate's name is the grant";
  EXPECT_EQ(List(address, server_cert, dir.path(), "stranger").error_code(),
            grpc::StatusCode::UNAUTHENTICATED)
      << "signed by the CA, but no grant of that name";
  EXPECT_TRUE(List(address, server_cert, dir.path(), "stranger", admin).ok())
      << "a token still grants, over the certified connection";
  EXPECT_EQ(List(address, server_cert, dir.path(), "").error_code(), grpc::StatusCode::UNAVAILABLE)
      << "no client certificate: the handshake fails";
}

TEST(TlsCredentialsTest, ServesARenewedCertificateWithoutARestart) {
  testing::ScratchDir dir;
  const std::filesystem::path old_dir = dir / "old", new_dir = dir / "new";
  std::filesystem::create_directories(old_dir);
  std::filesystem::create_directories(new_dir);
  testing::MakeSelfSignedCertificate(old_dir, "localhost", "DNS:localhost");
  testing::MakeSelfSignedCertificate(new_dir, "localhost", "DNS:localhost");
  std::filesystem::copy_file(old_dir / "cert.pem", dir / "cert.pem");
  std::filesystem::copy_file(old_dir / "key.pem", dir / "key.pem");
  ServerProcess server({.tls_cert = dir / "cert.pem", .tls_key = dir / "key.pem"});
  const std::string address = "localhost:" + std::to_string(server.port());
  const std::string old_cert = Slurp(old_dir / "cert.pem"), new_cert = Slurp(new_dir / "cert.pem");
  ASSERT_TRUE(List(address, old_cert, dir.path(), "").ok());
  EXPECT_FALSE(List(address, new_cert, dir.path(), "").ok());

  // Renewed as a deployment renews: the new files moved into place.
  std::filesystem::copy_file(new_dir / "key.pem", dir / "key.pem.next");
  std::filesystem::copy_file(new_dir / "cert.pem", dir / "cert.pem.next");
  std::filesystem::rename(dir / "key.pem.next", dir / "key.pem");
  std::filesystem::rename(dir / "cert.pem.next", dir / "cert.pem");
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::seconds(3 * server::kCertificateRefreshSeconds);
  while (!List(address, new_cert, dir.path(), "").ok() &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
  EXPECT_TRUE(List(address, new_cert, dir.path(), "").ok()) << server.Log();
  EXPECT_FALSE(List(address, old_cert, dir.path(), "").ok()) << "the old one is served no more";
}

}  // namespace
}  // namespace orbit
