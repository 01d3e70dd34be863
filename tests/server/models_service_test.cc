// The Models service's enrollment (server/models_service.h) against a real `orbit serve`
// process: however a view reaches the store, the same image stores the same numbers.
#include "server/models_service.h"
#include "core/engines/product_pipeline.h"

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <ostream>
#include <string>
#include <vector>

#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "client/enroller.h"
#include "client/image_file.h"
#include "client/models_client.h"
#include "evaluation/evaluation_runner.h"
#include "storage/sqlite_model_store.h"
#include "tests/support/client_test_support.h"
#include "tests/support/server_process.h"
#include "tests/support/storage_test_support.h"
#include "tests/support/synthetic_descriptor.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

using testing::CoilFile;
using testing::RunOrbit;
using testing::ScratchDir;
using testing::ServerProcess;

constexpr int kObject = 3;
const std::vector<int> kAzimuths = {0, 20, 40};

// One stored view's numbers.
struct Numbers {
  std::string cedd;
  double typical_distance = 0;
  friend bool operator==(const Numbers&, const Numbers&) = default;
  friend void PrintTo(const Numbers& n, std::ostream* out) {
    *out << "{cedd";
    for (char c : n.cedd) *out << ' ' << int(static_cast<std::uint8_t>(c));
    *out << ", Ttyp " << std::setprecision(17) << n.typical_distance << "}";
  }
};

std::vector<Numbers> FromWire(const v1::GetObjectResponse& object) {
  std::vector<Numbers> numbers;
  for (const v1::View& view : object.views()) {
    numbers.push_back({view.cedd(), view.typical_distance()});
  }
  return numbers;
}

std::string Cedd(const DescriptorValues& values) {
  return {values.begin(), values.begin() + kCeddSize};
}

TEST(ModelsServiceTest, EveryEnrollmentPathStoresTheSameNumbersForTheSameImage) {
  ScratchDir dir;
  ServerProcess server;
  const Connection connection(testing::At(server.address()));
  ModelsClient models(connection);

  // 1. The client library describes the images on the device and sends descriptors.
  std::vector<EnrollmentImage> images;
  for (int a : kAzimuths) {
    images.push_back({testing::CoilImage(kObject, a), static_cast<double>(a), {}, {}});
  }
  Enroller(connection, {.threads = 2}).Enroll("device", images);
  const std::vector<Numbers> device = FromWire(models.GetObject(ObjectByName("device"), true));

  // 2. A client without the library sends the encoded images; the server describes them.
  {
    grpc::ClientContext context;
    v1::ObjectInfo info;
    auto stub = v1::Models::NewStub(connection.channel());
    auto stream = stub->Enroll(&context, &info);
    v1::EnrollRequest request;
    request.mutable_header()->set_name("uploaded");
    ASSERT_TRUE(stream->Write(request));
    for (int a : kAzimuths) {
      std::vector<std::uint8_t> png;
      cv::imencode(".png", testing::CoilImage(kObject, a), png);
      v1::View* view = request.mutable_view();
      view->set_image(png.data(), png.size());
      view->set_azimuth_deg(a);
      ASSERT_TRUE(stream->Write(request));
    }
    stream->WritesDone();
    ASSERT_TRUE(stream->Finish().ok());
  }
  const std::vector<Numbers> uploaded = FromWire(models.GetObject(ObjectByName("uploaded"), true));

  // 3 and 4. orbit import, into a store file and onto the server.
  const std::filesystem::path manifest = dir / "views.csv";
  {
    std::ofstream csv(manifest);
    csv << "path,object,azimuth\n";
    for (int a : kAzimuths) csv << CoilFile(kObject, a) << ",imported," << a << "\n";
  }
  const std::string db = (dir / "models.db").string();
  ASSERT_EQ(RunOrbit("import --db " + db + " --layout manifest --manifest " + manifest.string())
                .exit_code,
            0);
  std::vector<Numbers> imported_file;
  const std::vector<ObjectModel> stored = SqliteModelStore(db).LoadAll();
  ASSERT_EQ(stored.size(), 1u);
  for (const ModelView& view : stored[0].views) {
    imported_file.push_back({Cedd(view.descriptor), view.typical_distance});
  }
  const auto remote = RunOrbit("import --server " + server.address() +
                               " --layout manifest --manifest " + manifest.string());
  ASSERT_EQ(remote.exit_code, 0) << remote.err;
  const std::vector<Numbers> imported_remote =
      FromWire(models.GetObject(ObjectByName("imported"), true));

  // 5. The evaluation harness, with its default seed.
  std::vector<Numbers> evaluated;
  for (std::size_t i = 0; i < kAzimuths.size(); ++i) {
    const DatasetImage image{CoilFile(kObject, kAzimuths[i]), "obj3", double(kAzimuths[i]), {}, {}};
    const ModelView view =
        DescribeImage(image, i, {Product().variant}, {}, EvaluationOptions{}.seed).at(0).view;
    evaluated.push_back({Cedd(view.descriptor), view.typical_distance});
  }

  // Equal to the last bit, and not trivially: real descriptors, typical distances in (0, 1).
  ASSERT_EQ(device.size(), kAzimuths.size());
  for (const Numbers& n : device) {
    EXPECT_EQ(n.cedd.size(), 144u);
    EXPECT_GT(n.typical_distance, 0.01);
    EXPECT_LT(n.typical_distance, 1.0);
  }
  EXPECT_NE(device[0], device[1]);
  EXPECT_EQ(uploaded, device);
  EXPECT_EQ(imported_file, device);
  EXPECT_EQ(imported_remote, device);
  EXPECT_EQ(evaluated, device);
}

// An object whose views and thumbnails outgrow a default client's 4 MiB receive limit comes in
// pages of at most about 3 MiB, which together hold every view in order; before, one 6 MB
// answer failed at the client.
TEST(ModelsServiceTest, AnObjectLargerThanOneResponseComesInPages) {
  ServerProcess server;
  auto models = v1::Models::NewStub(
      grpc::CreateChannel(server.address(), grpc::InsecureChannelCredentials()));
  constexpr int kViews = 100;
  {
    grpc::ClientContext context;
    v1::ObjectInfo info;
    auto writer = models->Enroll(&context, &info);
    v1::EnrollRequest header;
    header.mutable_header()->set_name("big");
    ASSERT_TRUE(writer->Write(header));
    for (int i = 0; i < kViews; ++i) {
      v1::EnrollRequest view;
      testing::SetDescriptor(*view.mutable_view(), testing::UniformDescriptor(i % 8));
      view.mutable_view()->set_azimuth_deg(i * 3.6);
      view.mutable_view()->set_thumbnail(std::string(60000, static_cast<char>('a' + i % 26)));
      ASSERT_TRUE(writer->Write(view));
    }
    writer->WritesDone();
    const grpc::Status enrolled = writer->Finish();
    ASSERT_TRUE(enrolled.ok()) << enrolled.error_message();
  }
  v1::GetObjectRequest request;
  request.mutable_object()->set_name("big");
  request.set_include_views(true);
  request.set_include_thumbnails(true);
  std::vector<v1::View> views;
  int pages = 0;
  do {
    grpc::ClientContext context;
    v1::GetObjectResponse page;
    const grpc::Status status = models->GetObject(&context, request, &page);
    ASSERT_TRUE(status.ok()) << status.error_message();
    EXPECT_LE(page.ByteSizeLong(), std::size_t{3} << 20);
    EXPECT_EQ(page.object().name(), "big");
    views.insert(views.end(), page.views().begin(), page.views().end());
    request.set_view_offset(page.next_view_offset());
    ++pages;
  } while (request.view_offset() > 0);
  EXPECT_GE(pages, 2);
  ASSERT_EQ(views.size(), std::size_t{kViews});
  for (int i = 0; i < kViews; ++i) {
    EXPECT_NEAR(views[i].azimuth_deg(), i * 3.6, 1e-9);
    EXPECT_EQ(views[i].thumbnail(), std::string(60000, static_cast<char>('a' + i % 26))) << i;
  }
  request.set_view_offset(kViews + 1);
  grpc::ClientContext context;
  v1::GetObjectResponse past;
  const grpc::Status status = models->GetObject(&context, request, &past);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(status.error_message(), "view_offset is 101, expected 0..100");
}

}  // namespace
}  // namespace orbit
