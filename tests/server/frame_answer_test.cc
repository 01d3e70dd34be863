// The one path a Session stream's frames and a Recognize call's take (server/frame_answer.h), on
// a real SQLite store, catalogue, calibrator and metrics.
#include "server/frame_answer.h"

#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "storage/sqlite_model_store.h"
#include "tests/support/coil_models.h"
#include "tests/support/storage_test_support.h"

namespace orbit::server {
namespace {

using orbit::testing::CoilObjects;
using orbit::testing::CoilView;
using orbit::testing::EvenView;
using orbit::testing::ScratchDir;
using ::testing::HasSubstr;

// A server's shared state around a store holding COIL-100 objects 1-4 (every other view).
class FrameAnswerTest : public ::testing::Test {
 protected:
  FrameAnswerTest()
      : store_(dir_ / "models.db",
               [] {
                 SqliteModelStoreOptions options;
                 options.create_if_missing = true;
                 return options;
               }()),
        catalogue_(store_, DescriptorVariant::kCeddLire, {}) {
    catalogue_.Load();
    for (const ObjectModel& model : CoilObjects(1, 4, EvenView)) {
      Enrollment enrollment;
      enrollment.name = model.name;
      enrollment.views = model.views;
      ids_.push_back(catalogue_.Enroll(enrollment).id);
    }
    calibrator_ = std::make_unique<RejectionCalibrator>(catalogue_.Snapshot());
  }

  SessionEnvironment Environment() {
    return {catalogue_, *calibrator_, pool_, pool_, registry_, limits_, defaults_, metrics_, gate_};
  }

  // A frame carrying the CEDD of COIL object `object` seen from `azimuth`.
  static v1::Frame Frame(int object, int azimuth) {
    const DescriptorValues& values = CoilView(object, azimuth);
    v1::Frame frame;
    frame.set_cedd(std::string(values.begin(), values.begin() + kCeddSize));
    frame.set_azimuth_deg(azimuth);
    return frame;
  }

  ScratchDir dir_;
  SqliteModelStore store_;
  ModelCatalogue catalogue_;
  std::vector<ObjectId> ids_;
  std::unique_ptr<RejectionCalibrator> calibrator_;
  WorkerPool pool_{1, 0, 32};
  SessionRegistry registry_{{.max_open = 4}};
  ServerLimits limits_;
  SessionSettings defaults_;
  ServerMetrics metrics_;
  ServingGate gate_;
};

TEST_F(FrameAnswerTest, OptionsOutOfRangeAreRefusedNamingTheFieldAndOpenNothing) {
  v1::SessionOptions requested;
  requested.set_window(65);
  OpenedSession session;
  RefusalReason reason = RefusalReason::kInternal;
  const grpc::Status status = OpenSession(requested, Environment(), &session, &reason);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(status.error_message(), "options.window must be in 1..64, got 65");
  EXPECT_EQ(reason, RefusalReason::kInvalidField);
  EXPECT_EQ(session.engine, nullptr);
}

TEST_F(FrameAnswerTest, AFrameIsAnsweredStampedAndCountedABadOneRefusedWithoutEffect) {
  v1::SessionOptions requested;
  requested.set_engine(v1::ENGINE_VCI_HMM);
  OpenedSession session;
  RefusalReason reason = RefusalReason::kInternal;
  ASSERT_TRUE(OpenSession(requested, Environment(), &session, &reason).ok());
  EXPECT_EQ(session.engine->name(), "vci-hmm");

  v1::Frame frame = Frame(3, 45);
  frame.set_timestamp_us(1234);
  v1::SessionUpdate update;
  ASSERT_TRUE(AnswerFrame(frame, std::chrono::steady_clock::now(), catalogue_.Snapshot(),
                          Environment(), session, &update, &reason)
                  .ok());
  EXPECT_EQ(update.frame_index(), 0);
  ASSERT_GT(update.candidates_size(), 0);
  EXPECT_EQ(update.candidates(0).id(), ids_[2]);
  EXPECT_EQ(update.candidates(0).name(), "obj3");
  EXPECT_EQ(update.timestamp_us(), 1234);
  EXPECT_GE(update.processing_time_us(), 0);
  EXPECT_THAT(metrics_.Expose(), HasSubstr("orbit_frames_processed_total{engine=\"vci-hmm\"} 1\n"));

  v1::Frame blurred = Frame(3, 55);
  blurred.mutable_quality()->set_blur(2);
  v1::SessionUpdate refused;
  const grpc::Status status =
      AnswerFrame(blurred, std::chrono::steady_clock::now(), catalogue_.Snapshot(), Environment(),
                  session, &refused, &reason);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(status.error_message(), "frame.quality.blur must be in [0, 1], got 2");
  EXPECT_EQ(reason, RefusalReason::kInvalidField);

  // The refused frame never reached the window: the next one is the second.
  ASSERT_TRUE(AnswerFrame(Frame(3, 55), std::chrono::steady_clock::now(), catalogue_.Snapshot(),
                          Environment(), session, &update, &reason)
                  .ok());
  EXPECT_EQ(update.frame_index(), 1);
  EXPECT_EQ(update.candidates(0).id(), ids_[2]);
}

}  // namespace
}  // namespace orbit::server
