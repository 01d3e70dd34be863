// The client library's model management, enrollment, errors, deadlines, tokens and TLS, against
// a real `orbit serve` process (tests/support/server_process.h).
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

#include "client/connection.h"
#include "client/enroller.h"
#include "client/models_client.h"
#include "client/recognition_session.h"
#include "client/rpc_error.h"
#include "core/cedd.h"
#include "core/view_description.h"
#include "tests/support/client_test_support.h"
#include "tests/support/server_process.h"

namespace orbit {
namespace {

using testing::CoilEnrollmentImages;
using testing::CoilImage;
using testing::EnrollCoilObjects;
using testing::ServerProcess;

// The status code of the RpcError `call` throws; OK when it throws nothing.
template <typename Call>
grpc::StatusCode CodeOf(Call call) {
  try {
    call();
  } catch (const RpcError& e) {
    return e.code();
  }
  return grpc::StatusCode::OK;
}

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

TEST(ClientLibrary, ComputeViewIsTheCeddAndTypicalDistanceOfTheImageOrRegion) {
  const cv::Mat image = CoilImage(7, 40);
  const v1::View view =
      ComputeView({image, 40.0, std::nullopt, 12.5}, DescriptorVariant::kCeddLire, /*seed=*/9);
  const DescriptorValues expected = ExtractCedd(image, DescriptorVariant::kCeddLire).values;
  EXPECT_EQ(view.cedd(), std::string(expected.begin(), expected.end()));
  EXPECT_EQ(view.azimuth_deg(), 40.0);
  EXPECT_EQ(view.elevation_deg(), 12.5);
  ASSERT_TRUE(view.has_typical_distance());
  EXPECT_DOUBLE_EQ(view.typical_distance(),
                   DescribeView(image, DescriptorVariant::kCeddLire, 9).typical_distance);
  EXPECT_GT(view.typical_distance(), 0.0);
  EXPECT_LT(view.typical_distance(), 1.0);

  // With a region, everything is computed on the region alone, as if the device had cropped.
  const cv::Rect region(20, 30, 80, 70);
  const v1::View cropped =
      ComputeView({image, 40.0, region, std::nullopt}, DescriptorVariant::kCeddFull, 9);
  const cv::Mat crop = image(region).clone();
  const DescriptorValues crop_cedd = ExtractCedd(crop, DescriptorVariant::kCeddFull).values;
  EXPECT_EQ(cropped.cedd(), std::string(crop_cedd.begin(), crop_cedd.end()));
  EXPECT_DOUBLE_EQ(cropped.typical_distance(),
                   DescribeView(crop, DescriptorVariant::kCeddFull, 9).typical_distance);
  EXPECT_FALSE(cropped.has_elevation_deg());

  EXPECT_THROW(ComputeView({image, 0, cv::Rect(100, 100, 40, 40), {}},
                           DescriptorVariant::kCeddLire, 1),
               std::invalid_argument);
  EXPECT_THROW(ComputeView({cv::Mat(), 0, {}, {}}, DescriptorVariant::kCeddLire, 1),
               std::invalid_argument);
}

TEST(ClientLibrary, EnrollsListsGetsAndDeletesObjects) {
  ServerProcess server;
  const Connection connection(testing::At(server.address()));
  ModelsClient models(connection);
  EXPECT_EQ(models.ServerInfo().object_count(), 0);

  EnrollCoilObjects(connection, 1, 3);
  const v1::ServerInfoResponse info = models.ServerInfo();
  EXPECT_EQ(info.object_count(), 3);
  EXPECT_EQ(info.view_count(), 3 * 36);
  EXPECT_EQ(info.variant(), v1::CEDD_LIRE);

  // Paged listing: two pages of two and one, in id order.
  const v1::ListObjectsResponse first = models.ListObjects(2);
  ASSERT_EQ(first.objects_size(), 2);
  EXPECT_EQ(first.objects(0).name(), "obj1");
  EXPECT_EQ(first.objects(1).name(), "obj2");
  ASSERT_FALSE(first.next_page_token().empty());
  const v1::ListObjectsResponse second = models.ListObjects(2, first.next_page_token());
  ASSERT_EQ(second.objects_size(), 1);
  EXPECT_EQ(second.objects(0).name(), "obj3");
  EXPECT_TRUE(second.next_page_token().empty());
  const std::vector<v1::ObjectInfo> all = models.ListAllObjects();
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[2].view_count(), 36);

  // The stored views are the ones computed on the device, ordered by azimuth.
  const v1::GetObjectResponse obj2 = models.GetObject(ObjectByName("obj2"), true);
  ASSERT_EQ(obj2.views_size(), 36);
  EXPECT_EQ(obj2.views(1).azimuth_deg(), 10.0);
  const v1::View expected =
      ComputeView(CoilEnrollmentImages(2)[1], DescriptorVariant::kCeddLire);
  EXPECT_EQ(obj2.views(1).cedd(), expected.cedd());
  EXPECT_NEAR(obj2.views(1).typical_distance(), expected.typical_distance(), 1e-12);

  // Adding views, then deleting.
  const v1::ObjectInfo grown = models.AddViews(
      ObjectById(obj2.object().id()),
      {ComputeView({CoilImage(2, 5), 5.0, {}, {}}, DescriptorVariant::kCeddLire, 3)});
  EXPECT_EQ(grown.view_count(), 37);
  const v1::ObjectInfo deleted = models.DeleteObject(ObjectByName("obj1"));
  EXPECT_EQ(deleted.name(), "obj1");
  EXPECT_EQ(models.ListAllObjects().size(), 2u);

  // Refusals arrive as RpcError with the server's code.
  EXPECT_EQ(CodeOf([&] { models.GetObject(ObjectByName("obj1")); }),
            grpc::StatusCode::NOT_FOUND);
  EXPECT_EQ(CodeOf([&] { models.DeleteObject(ObjectById(999)); }), grpc::StatusCode::NOT_FOUND);
  Enroller enroller(connection);
  EXPECT_EQ(CodeOf([&] { enroller.Enroll("obj2", CoilEnrollmentImages(2)); }),
            grpc::StatusCode::ALREADY_EXISTS);
  EXPECT_EQ(CodeOf([&] { enroller.Enroll("bad name!", CoilEnrollmentImages(4)); }),
            grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(models.ServerInfo().object_count(), 2);  // the refused enrollments left nothing
}

TEST(ClientLibrary, UnreachableAndSilentServersFailWithinTheDeadline) {
  const Connection nobody(testing::At(RefusedAddress(), std::chrono::milliseconds(2000)));
  EXPECT_EQ(CodeOf([&] { ModelsClient(nobody).ServerInfo(); }), grpc::StatusCode::UNAVAILABLE);
  EXPECT_EQ(CodeOf([&] { RecognitionSession::Open(nobody, {}); }),
            grpc::StatusCode::UNAVAILABLE);

  // A server that never answers: the call ends at its deadline.
  const SilentServer silent;
  const Connection mute(testing::At(silent.address(), std::chrono::milliseconds(300)));
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(CodeOf([&] { ModelsClient(mute).ServerInfo(); }),
            grpc::StatusCode::DEADLINE_EXCEEDED);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));

  try {
    ModelsClient(nobody).ServerInfo();
    FAIL() << "no error";
  } catch (const RpcError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("ServerInfo: UNAVAILABLE", 0), 0u) << e.what();
  }
}

TEST(ClientLibrary, TokensAndTlsReachTheServer) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("orbit_client_tls_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  {
    std::ofstream tokens(dir / "tokens");
    tokens << "# operators\nadmin-secret-0001 admin\nreader-secret-0001 recognize\n";
    std::ofstream token_file(dir / "reader.token");
    token_file << "# the device's token\nreader-secret-0001\n";
  }
  const std::string make_cert =
      "openssl req -x509 -newkey rsa:2048 -nodes -days 2 -subj /CN=orbit.test "
      "-addext subjectAltName=DNS:orbit.test -keyout " + (dir / "key.pem").string() +
      " -out " + (dir / "cert.pem").string() + " 2>/dev/null";
  ASSERT_EQ(std::system(make_cert.c_str()), 0) << "openssl could not make a test certificate";
  testing::ServerProcessOptions server_options;
  server_options.tokens_file = dir / "tokens";
  server_options.tls_cert = dir / "cert.pem";
  server_options.tls_key = dir / "key.pem";
  ServerProcess server(server_options);
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
  EXPECT_EQ(CodeOf([&] { ModelsClient(reader_connection).DeleteObject(ObjectByName("obj1")); }),
            grpc::StatusCode::PERMISSION_DENIED);
  auto session = RecognitionSession::Open(reader_connection, {});
  session->Push(CoilImage(1, 15), 15);
  const std::optional<v1::SessionUpdate> update = session->NextUpdate();
  ASSERT_TRUE(update.has_value());
  ASSERT_GT(update->candidates_size(), 0);
  EXPECT_EQ(update->candidates(0).name(), "obj1");
  EXPECT_TRUE(session->Close().ok());

  const Connection anonymous(tls);
  EXPECT_EQ(CodeOf([&] { ModelsClient(anonymous).ServerInfo(); }),
            grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_EQ(CodeOf([&] { RecognitionSession::Open(anonymous, {}); }),
            grpc::StatusCode::UNAUTHENTICATED);
  ConnectionOptions plaintext = admin;
  plaintext.tls_root_certificates_file.clear();
  EXPECT_EQ(CodeOf([&] { ModelsClient(Connection(plaintext)).ServerInfo(); }),
            grpc::StatusCode::UNAVAILABLE);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace orbit
