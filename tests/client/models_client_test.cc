// The operator's calls (client/models_client.h) and enrollment (client/enroller.h) against a
// real `orbit serve` process (tests/support/server_process.h): enroll, list, get, add views,
// delete, and the server's refusals as RpcError codes.
#include "client/models_client.h"

#include <gtest/gtest.h>

#include "api/conversion.h"
#include "client/enroller.h"
#include "client/rpc_error.h"
#include "tests/support/client_test_support.h"
#include "tests/support/server_process.h"

namespace orbit {
namespace {

using testing::CoilEnrollmentImages;
using testing::CoilImage;
using testing::EnrollCoilObjects;
using testing::RpcCodeOf;
using testing::ServerProcess;

TEST(ModelsClientTest, EnrollsListsGetsAndDeletesObjects) {
  ServerProcess server;
  const Connection connection(testing::At(server.address()));
  ModelsClient models(connection);
  EXPECT_EQ(models.ServerInfo().object_count(), 0);

  EnrollCoilObjects(connection, 1, 3);
  const v1::ServerInfoResponse info = models.ServerInfo();
  EXPECT_EQ(info.object_count(), 3);
  EXPECT_EQ(info.view_count(), 3 * 36);
  EXPECT_EQ(info.variant(), v1::CEDD_SOFT_HSV_HOG);  // the product's, for a new store
  const DescriptorVariant variant = FromProtoVariant(info.variant());

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
  const v1::View expected = ComputeView(CoilEnrollmentImages(2)[1], variant);
  EXPECT_EQ(obj2.views(1).cedd(), expected.cedd());
  EXPECT_NEAR(obj2.views(1).typical_distance(), expected.typical_distance(), 1e-12);

  // Adding views, then deleting.
  const v1::ObjectInfo grown = models.AddViews(
      ObjectById(obj2.object().id()), {ComputeView({CoilImage(2, 5), 5.0, {}, {}}, variant, 3)});
  EXPECT_EQ(grown.view_count(), 37);
  const v1::ObjectInfo deleted = models.DeleteObject(ObjectByName("obj1"));
  EXPECT_EQ(deleted.name(), "obj1");
  EXPECT_EQ(models.ListAllObjects().size(), 2u);

  // Refusals arrive as RpcError with the server's code.
  EXPECT_EQ(RpcCodeOf([&] { models.GetObject(ObjectByName("obj1")); }),
            grpc::StatusCode::NOT_FOUND);
  EXPECT_EQ(RpcCodeOf([&] { models.DeleteObject(ObjectById(999)); }), grpc::StatusCode::NOT_FOUND);
  Enroller enroller(connection);
  EXPECT_EQ(RpcCodeOf([&] { enroller.Enroll("obj2", CoilEnrollmentImages(2)); }),
            grpc::StatusCode::ALREADY_EXISTS);
  EXPECT_EQ(RpcCodeOf([&] { enroller.Enroll("bad name!", CoilEnrollmentImages(4)); }),
            grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(models.ServerInfo().object_count(), 2);  // the refused enrollments left nothing
}

}  // namespace
}  // namespace orbit
