// RunServerEvaluation against a real `orbit serve` on loopback: what it counts, and that a
// session read after its n-th frame answers as a user's session of just those n frames.
#include "evaluation/server_evaluation.h"

#include <cmath>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "api/conversion.h"
#include "api/engines/conversion.h"
#include "api/engines/engine_names.h"
#include "core/engines/product_pipeline.h"
#include "server/session_settings.h"
#include "tests/support/client_test_support.h"
#include "tests/support/server_process.h"

namespace orbit {
namespace {

using testing::At;
using testing::CoilEnrollmentImages;
using testing::CoilFile;
using testing::ServerProcess;

// The ServerInfo of a server with the product's defaults: what `orbit serve` reports
// (server/session_settings.h).
v1::ServerInfoResponse ProductInfo() {
  v1::ServerInfoResponse info;
  info.set_variant(ToProtoVariant(Product().variant));
  *info.mutable_session_defaults() =
      server::DescribeSettings(server::SessionSettings{}, Product().variant);
  return info;
}

TEST(ServerMethodNameTest, NamesTheProductOnlyWhenEveryDefaultShownIsTheProducts) {
  EXPECT_EQ(ServerMethodName(ProductInfo()), "server (product)");
  v1::ServerInfoResponse info = ProductInfo();
  info.mutable_session_defaults()->set_window(12);
  EXPECT_EQ(ServerMethodName(info), "server (" + SessionEngineName(ProductSessionEngine()) + ")");
  info = ProductInfo();
  info.mutable_session_defaults()->set_engine(v1::ENGINE_VCI);
  EXPECT_EQ(ServerMethodName(info), "server (vci)");
  info = ProductInfo();
  info.set_variant(v1::CEDD_LIRE);
  EXPECT_EQ(ServerMethodName(info), "server (" + SessionEngineName(ProductSessionEngine()) + ")");
}

// Objects 1 and 2 of COIL-100 enrolled every 10 degrees; queries of them between their views,
// and of object 7, which the server does not hold.
class ServerEvaluationTest : public ::testing::Test {
 protected:
  void SetUp() override {
    Enroller enroller(connection_);
    enroller.Enroll("obj1", CoilEnrollmentImages(1));
    enroller.Enroll("obj2", CoilEnrollmentImages(2));
    for (const auto& [object, sequence, first] :
         std::vector<std::tuple<int, std::string, int>>{{1, "a", 5}, {2, "b", 105}, {7, "c", 5}}) {
      for (int k = 0; k < 3; ++k) {
        const int azimuth = first + 10 * k;
        captures_.push_back({CoilFile(object, azimuth), "obj" + std::to_string(object),
                             static_cast<double>(azimuth + 30), sequence, ""});
      }
    }
  }

  ServerProcess server_;
  Connection connection_{At(server_.address())};
  std::vector<CaptureFrame> captures_;
};

TEST_F(ServerEvaluationTest, CountsEachSequenceAtEveryNAsAFreshSessionOfNFramesAnswersIt) {
  ServerEvaluationOptions options;
  options.query_lengths = {1, 2, 3};
  const EvaluationReport report = RunServerEvaluation(connection_, captures_, options);
  ASSERT_TRUE(report.server.has_value());
  EXPECT_EQ(report.server->address, server_.address());
  EXPECT_EQ(report.server->views, 72u);
  EXPECT_TRUE(report.server->runs_product);
  EXPECT_EQ(report.known_objects, 2u);
  EXPECT_EQ(report.unknown_objects, 1u);
  EXPECT_EQ(report.query_sequences, 3u);
  EXPECT_EQ(report.query_frames, 9u);
  ASSERT_EQ(report.cells.size(), 3u);

  for (const EvaluationCell& cell : report.cells) {
    EXPECT_EQ(cell.method, "server (product)");
    EXPECT_EQ(cell.variant, Product().variant);
    EXPECT_EQ(cell.trials, 2);  // objects 1 and 2
    EXPECT_EQ(cell.hits, 2);    // views 5 degrees from enrolled ones
    EXPECT_EQ(cell.unknown_trials, 1);
    ASSERT_EQ(cell.verdicts.size(), 3u);  // in the sequences' order
    // A user's own session of the sequence's first n frames.
    for (std::size_t s = 0; s < 3; ++s) {
      auto session = RecognitionSession::Open(connection_, {});
      for (int k = 0; k < cell.n; ++k) {
        const CaptureFrame& frame = captures_[3 * s + static_cast<std::size_t>(k)];
        session->Push(ReadImageFile(frame.path), frame.azimuth);
      }
      ASSERT_TRUE(session->Close().ok());
      std::optional<v1::SessionUpdate> last;
      while (std::optional<v1::SessionUpdate> update = session->NextUpdate()) last = update;
      ASSERT_TRUE(last.has_value());
      const QueryVerdict& verdict = cell.verdicts[s];
      EXPECT_EQ(verdict.known, s < 2);
      EXPECT_EQ(verdict.decision, FromProtoDecision(last->decision())) << "n=" << cell.n;
      EXPECT_EQ(verdict.confidence, last->confidence()) << "n=" << cell.n;
      EXPECT_EQ(verdict.hit, s < 2 && last->candidates(0).name() == captures_[3 * s].object);
      EXPECT_TRUE(std::isnan(verdict.unknown_p_value));
    }
  }
}

TEST_F(ServerEvaluationTest, ASequenceShorterThanNIsNotCountedAtN) {
  captures_.resize(7);  // sequence "c" keeps one frame
  ServerEvaluationOptions options;
  options.query_lengths = {1, 2};
  const EvaluationReport report = RunServerEvaluation(connection_, captures_, options);
  ASSERT_EQ(report.cells.size(), 2u);
  EXPECT_EQ(report.cells[0].unknown_trials, 1);
  EXPECT_EQ(report.cells[1].unknown_trials, 0);
  EXPECT_EQ(report.cells[1].trials, 2);
}

TEST_F(ServerEvaluationTest, DescribesEachFrameInItsBoxGrownByTheMargin) {
  ServerEvaluationOptions options;
  options.query_lengths = {2};
  options.box_margin = 0.25;  // 40 x 40 grown by 10 px on each side: (34, 34, 60, 60)
  for (std::size_t f = 0; f < captures_.size(); ++f) {
    options.boxes[captures_[f].path] = ImageBox{44, 44, 40, 40, "boxes.csv:" + std::to_string(f)};
  }
  const EvaluationReport report = RunServerEvaluation(connection_, captures_, options);
  ASSERT_EQ(report.cells.size(), 1u);
  ASSERT_EQ(report.cells[0].verdicts.size(), 3u);
  // The second sequence (obj2's) as a device sends it with that region: the crop lies far
  // from every enrolled view, which the two-object catalogue's confidence says.
  auto session = RecognitionSession::Open(connection_, {});
  for (std::size_t f = 3; f < 5; ++f) {
    session->Push(ReadImageFile(captures_[f].path), captures_[f].azimuth, cv::Rect(34, 34, 60, 60));
  }
  ASSERT_TRUE(session->Close().ok());
  std::optional<v1::SessionUpdate> last;
  while (std::optional<v1::SessionUpdate> update = session->NextUpdate()) last = update;
  ASSERT_TRUE(last.has_value());
  EXPECT_EQ(report.cells[0].verdicts[1].confidence, last->confidence());
  // ... which is not what the whole frames give.
  options.boxes.clear();
  const EvaluationReport whole = RunServerEvaluation(connection_, captures_, options);
  EXPECT_NE(whole.cells[0].verdicts[1].confidence, last->confidence());

  options.boxes[captures_[0].path] = ImageBox{100, 100, 40, 40, "boxes.csv:2"};
  for (std::size_t f = 1; f < captures_.size(); ++f) options.boxes[captures_[f].path] = {};
  EXPECT_THAT(
      testing::ErrorMessageOf([&] { RunServerEvaluation(connection_, captures_, options); }),
      ::testing::StartsWith("boxes.csv:2"));
}

TEST_F(ServerEvaluationTest, RefusesBadQueryLengthsAndFramesWithoutABox) {
  ServerEvaluationOptions options;
  options.query_lengths = {0};
  EXPECT_EQ(testing::ErrorMessageOf([&] { RunServerEvaluation(connection_, captures_, options); }),
            "n = 0 is outside 1..64");
  options.query_lengths = {1};
  options.boxes[captures_[0].path] = ImageBox{0, 0, 64, 64, "boxes.csv:2"};
  EXPECT_EQ(testing::ErrorMessageOf([&] { RunServerEvaluation(connection_, captures_, options); }),
            "no box for " + captures_[1].path);
}

}  // namespace
}  // namespace orbit
