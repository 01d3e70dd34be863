// The gRPC service end to end: a real `orbit serve` process on a loopback port, spoken to through
// the generated stubs, with COIL-100 views as the objects (docs/design.md#service-behaviour).
#include <gtest/gtest.h>

#include <signal.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <future>
#include <limits>
#include <map>
#include <thread>

#include <grpcpp/grpcpp.h>
#include <nlohmann/json.hpp>

#include "api/conversion.h"
#include "client/image_file.h"
#include "core/descriptor/cedd.h"
#include "core/descriptor/view_description.h"
#include "core/engines/product_pipeline.h"
#include "orbit/v1/models.grpc.pb.h"
#include "orbit/v1/recognition.grpc.pb.h"
#include "server/token_file.h"
#include "storage/postgres_connection.h"
#include "tests/support/free_port.h"
#include "tests/support/health_check.h"
#include "tests/support/postgres_test_cluster.h"
#include "tests/support/server_process.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

using testing::ServerProcess;
using testing::ServerProcessOptions;

// The descriptor of a COIL-100 view in the server's variant, cached across tests.
const DescriptorValues& CoilDescriptor(int object, int azimuth) {
  static std::map<std::pair<int, int>, DescriptorValues> cache;
  static std::mutex mutex;
  std::lock_guard lock(mutex);
  const auto found = cache.find({object, azimuth});
  if (found != cache.end()) return found->second;
  const cv::Mat image =
      ReadImageFile((testing::DataDir() / "coil-100" /
                     ("obj" + std::to_string(object) + "__" + std::to_string(azimuth) + ".png"))
                        .string());
  return cache[{object, azimuth}] = ExtractCedd(image, Product().variant).values;  // the server's
}

// A COIL-100 view's descriptor as a message's `cedd` and `appearance` fields carry it.
std::pair<std::string, std::string> CoilWire(int object, int azimuth) {
  std::pair<std::string, std::string> wire;
  SetWireDescriptor(CoilDescriptor(object, azimuth), Product().variant, &wire.first, &wire.second);
  return wire;
}

// Sets a frame's or view's `cedd` and `appearance` to a COIL-100 view's descriptor.
template <typename Message>
void SetCoilDescriptor(Message* message, int object, int azimuth) {
  SetWireDescriptor(CoilDescriptor(object, azimuth), Product().variant, message->mutable_cedd(),
                    message->mutable_appearance());
}

double CoilTypicalDistance(int object, int azimuth) {
  const cv::Mat image =
      ReadImageFile((testing::DataDir() / "coil-100" /
                     ("obj" + std::to_string(object) + "__" + std::to_string(azimuth) + ".png"))
                        .string());
  return DescribeView(image, Product().variant, 7).typical_distance;
}

class Client {
 public:
  explicit Client(
      const std::string& address, std::string token = "",
      std::shared_ptr<grpc::ChannelCredentials> credentials = grpc::InsecureChannelCredentials())
      : channel_(grpc::CreateChannel(address, credentials)),
        models_(v1::Models::NewStub(channel_)),
        recognition_(v1::Recognition::NewStub(channel_)),
        token_(std::move(token)) {}

  void Prepare(grpc::ClientContext& context) const {
    context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(30));
    if (!token_.empty()) context.AddMetadata("authorization", "Bearer " + token_);
  }

  // Enrolls COIL-100 object `object` under `name` with the views at `azimuths` (every 5 degrees
  // by default), optionally with typical distances computed as a device would.
  grpc::Status Enroll(const std::string& name, int object, v1::ObjectInfo* info,
                      std::vector<int> azimuths = {}, bool typical = false) const {
    if (azimuths.empty()) {
      for (int a = 0; a < 360; a += 5) azimuths.push_back(a);
    }
    std::vector<v1::EnrollRequest> requests(1);
    requests[0].mutable_header()->set_name(name);
    for (int a : azimuths) {
      v1::EnrollRequest r;
      SetCoilDescriptor(r.mutable_view(), object, a);
      r.mutable_view()->set_azimuth_deg(a);
      if (typical) r.mutable_view()->set_typical_distance(CoilTypicalDistance(object, a));
      requests.push_back(r);
    }
    return EnrollRaw(requests, info);
  }

  grpc::Status EnrollRaw(const std::vector<v1::EnrollRequest>& requests,
                         v1::ObjectInfo* info) const {
    grpc::ClientContext context;
    Prepare(context);
    auto writer = models_->Enroll(&context, info);
    for (const auto& r : requests) {
      if (!writer->Write(r)) break;
    }
    writer->WritesDone();
    return writer->Finish();
  }

  grpc::Status List(v1::ListObjectsResponse* response, int page_size = 0,
                    std::string token = "") const {
    grpc::ClientContext context;
    Prepare(context);
    v1::ListObjectsRequest request;
    request.set_page_size(page_size);
    request.set_page_token(token);
    return models_->ListObjects(&context, request, response);
  }

  grpc::Status Delete(const std::string& name) const {
    grpc::ClientContext context;
    Prepare(context);
    v1::DeleteObjectRequest request;
    request.mutable_object()->set_name(name);
    v1::DeleteObjectResponse response;
    return models_->DeleteObject(&context, request, &response);
  }

  grpc::Status Info(v1::ServerInfoResponse* response) const {
    grpc::ClientContext context;
    Prepare(context);
    return models_->ServerInfo(&context, v1::ServerInfoRequest(), response);
  }

  // One session: open with `options`, then each request; returns the updates and the status.
  struct SessionResult {
    std::vector<v1::SessionUpdate> updates;
    grpc::Status status;
  };
  SessionResult Session(const v1::SessionOptions& options,
                        const std::vector<v1::SessionRequest>& requests) const {
    grpc::ClientContext context;
    Prepare(context);
    auto stream = recognition_->Session(&context);
    SessionResult result;
    v1::SessionRequest open;
    *open.mutable_open() = options;
    stream->Write(open);
    for (const auto& r : requests) {
      if (!stream->Write(r)) break;
      if (r.has_frame()) {
        v1::SessionUpdate update;
        if (!stream->Read(&update)) break;
        result.updates.push_back(update);
      }
    }
    stream->WritesDone();
    v1::SessionUpdate extra;
    while (stream->Read(&extra)) result.updates.push_back(extra);
    result.status = stream->Finish();
    return result;
  }

  v1::Recognition::Stub& recognition() { return *recognition_; }

  // A session stream, opened with `options` (the `open` request already sent).
  using SessionStream = grpc::ClientReaderWriter<v1::SessionRequest, v1::SessionUpdate>;
  std::unique_ptr<SessionStream> OpenSession(grpc::ClientContext& context,
                                             const v1::SessionOptions& options = {}) {
    Prepare(context);
    auto stream = recognition_->Session(&context);
    v1::SessionRequest open;
    *open.mutable_open() = options;
    EXPECT_TRUE(stream->Write(open));
    return stream;
  }
  std::unique_ptr<grpc::ClientWriter<v1::EnrollRequest>> models_for_test(
      grpc::ClientContext* context, v1::ObjectInfo* info) {
    return models_->Enroll(context, info);
  }

 private:
  std::shared_ptr<grpc::Channel> channel_;
  std::unique_ptr<v1::Models::Stub> models_;
  std::unique_ptr<v1::Recognition::Stub> recognition_;
  std::string token_;
};

v1::SessionRequest CoilFrame(int object, int azimuth, double device_azimuth) {
  v1::SessionRequest r;
  SetCoilDescriptor(r.mutable_frame(), object, azimuth);
  r.mutable_frame()->set_azimuth_deg(device_azimuth);
  return r;
}

// Frames of `object` at model azimuths start, start+step, ..., seen by a device whose compass
// is off by `offset` degrees.
std::vector<v1::SessionRequest> CoilSweep(int object, int start, int step, int count,
                                          double offset) {
  std::vector<v1::SessionRequest> frames;
  for (int k = 0; k < count; ++k) {
    const int azimuth = (start + k * step) % 360;
    frames.push_back(CoilFrame(object, azimuth, azimuth + offset));
  }
  return frames;
}

// Views of an object with every view within 10 degrees of the query's removed, as the protocol
// does: the query's own views are not in the model.
std::vector<int> AzimuthsAwayFrom(int from, int to) {
  std::vector<int> kept;
  for (int a = 0; a < 360; a += 5) {
    if (a < from - 10 || a > to + 10) kept.push_back(a);
  }
  return kept;
}

// Enrolls each COIL-100 object as "obj<N>" with the views at `azimuths` (all 72 when empty).
void EnrollCoilObjects(const Client& client, const std::vector<int>& objects,
                       const std::vector<int>& azimuths = {}, bool typical = false) {
  for (int object : objects) {
    v1::ObjectInfo info;
    const grpc::Status s =
        client.Enroll("obj" + std::to_string(object), object, &info, azimuths, typical);
    ASSERT_TRUE(s.ok()) << "obj" << object << ": " << s.error_message();
  }
}

TEST(Server, EnrollsListsAndRecognisesCoilObjects) {
  ServerProcess server;
  Client client(server.address());
  // Objects 1..5; object 3 without the views near the query's, so the query is new to it.
  for (int object = 1; object <= 5; ++object) {
    v1::ObjectInfo info;
    const auto azimuths = object == 3 ? AzimuthsAwayFrom(100, 130) : std::vector<int>{};
    ASSERT_TRUE(client.Enroll("obj" + std::to_string(object), object, &info, azimuths).ok());
    EXPECT_EQ(info.name(), "obj" + std::to_string(object));
    EXPECT_EQ(info.view_count(), static_cast<int>(object == 3 ? azimuths.size() : 72));
    EXPECT_EQ(info.variant(), v1::CEDD_SOFT_HSV_HOG);
  }
  v1::ListObjectsResponse page1, page2;
  ASSERT_TRUE(client.List(&page1, 3).ok());
  ASSERT_EQ(page1.objects_size(), 3);
  EXPECT_EQ(page1.objects(0).name(), "obj1");
  ASSERT_FALSE(page1.next_page_token().empty());
  ASSERT_TRUE(client.List(&page2, 3, page1.next_page_token()).ok());
  ASSERT_EQ(page2.objects_size(), 2);
  EXPECT_EQ(page2.objects(1).name(), "obj5");
  EXPECT_TRUE(page2.next_page_token().empty());

  v1::ServerInfoResponse info;
  ASSERT_TRUE(client.Info(&info).ok());
  EXPECT_EQ(info.object_count(), 5);
  EXPECT_EQ(info.view_count(), 4 * 72 + static_cast<int>(AzimuthsAwayFrom(100, 130).size()));
  EXPECT_EQ(info.session_defaults().window(), 8);
  EXPECT_EQ(info.session_defaults().engine(), v1::ENGINE_HMM);
  EXPECT_EQ(info.limits().max_image_pixels(), 4096 * 4096);
  EXPECT_EQ(info.limits().max_hmm_cells(), 1024);
  EXPECT_EQ(info.limits().max_queued_calls(), 32);
  EXPECT_EQ(info.limits().max_sessions_per_token(), 64);
  EXPECT_EQ(info.limits().max_recognize_calls_per_token(), 8);
  EXPECT_EQ(info.limits().max_enrollments(), 4);
  EXPECT_EQ(info.limits().max_enrollment_bytes(), std::int64_t{256} << 20);
  EXPECT_EQ(info.limits().enrollment_idle_timeout_seconds(), 30);

  for (const v1::Engine engine : {v1::ENGINE_VCI, v1::ENGINE_HMM, v1::ENGINE_VCI_HMM}) {
    v1::SessionOptions options;
    options.set_engine(engine);
    options.set_top_k(3);
    // Device compass 200 degrees off the model's: only differences may matter.
    const auto result = client.Session(options, CoilSweep(3, 100, 10, 4, 200.0));
    ASSERT_TRUE(result.status.ok()) << engine << ": " << result.status.error_message();
    ASSERT_EQ(result.updates.size(), 4u) << engine;
    for (std::size_t k = 0; k < result.updates.size(); ++k) {
      EXPECT_EQ(result.updates[k].frame_index(), static_cast<std::int64_t>(k));
      EXPECT_LE(result.updates[k].candidates_size(), 3);
      EXPECT_NE(result.updates[k].move(), v1::MOVE_UNSPECIFIED);
      EXPECT_NE(result.updates[k].decision(), v1::DECISION_UNSPECIFIED);
    }
    ASSERT_GT(result.updates.back().candidates_size(), 0);
    EXPECT_EQ(result.updates.back().candidates(0).name(), "obj3") << engine;
  }
}

// Sessions that ask for no target rate take the store's variant's (ProductFalseAcceptRate), as
// `orbit info` shows a device, unless the operator gave one.
TEST(Server, SessionsTakeTheVariantsTargetRateUnlessTheOperatorGivesOne) {
  const auto served_rate = [](std::vector<std::string> args) {
    ServerProcess server({.extra_args = std::move(args)});
    v1::ServerInfoResponse info;
    const grpc::Status s = Client(server.address()).Info(&info);
    EXPECT_TRUE(s.ok()) << s.error_message();
    return info.session_defaults().false_accept_rate();
  };
  EXPECT_EQ(served_rate({}), kProductFalseAcceptRate);
  EXPECT_EQ(served_rate({"--variant", "cedd-hsv-layout"}), kLayoutFalseAcceptRate);
  EXPECT_EQ(served_rate({"--variant", "cedd-hsv-layout", "--false-accept-rate", "0.2"}), 0.2);
}

TEST(Server, RecognizeAnswersABatchLikeASession) {
  ServerProcess server;
  Client client(server.address());
  ASSERT_NO_FATAL_FAILURE(EnrollCoilObjects(client, {7, 8, 9}, AzimuthsAwayFrom(40, 70)));
  v1::RecognizeRequest request;
  request.mutable_options()->set_engine(v1::ENGINE_VCI);
  for (const auto& r : CoilSweep(8, 40, 10, 4, -55.0)) *request.add_frames() = r.frame();
  grpc::ClientContext context;
  client.Prepare(context);
  v1::RecognizeResponse response;
  ASSERT_TRUE(client.recognition().Recognize(&context, request, &response).ok());
  ASSERT_EQ(response.updates_size(), 4);
  EXPECT_EQ(response.updates(3).candidates(0).name(), "obj8");

  const auto session = client.Session(request.options(), CoilSweep(8, 40, 10, 4, -55.0));
  ASSERT_EQ(session.updates.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    ASSERT_EQ(session.updates[k].candidates_size(), response.updates(k).candidates_size());
    for (int c = 0; c < response.updates(k).candidates_size(); ++c) {
      EXPECT_EQ(session.updates[k].candidates(c).id(), response.updates(k).candidates(c).id());
      EXPECT_DOUBLE_EQ(session.updates[k].candidates(c).score(),
                       response.updates(k).candidates(c).score());
    }
  }
}

// The session's threshold Th decides ACCEPT / UNKNOWN from the typical distances the device sent.
// (In cedd-lire, with the default Th = 2 of docs/design.md#threshold-rule, nearly every
// untrained COIL-100 object is accepted: Gaussian noise of variance 0.012 moves a 128x128 CEDD so
// far that Ttyp is large, and twice it is more than almost any match's distance;
// docs/results/engines-speed.md, "Rejection threshold on COIL-100 (observation)". The product's
// variant moves far less under that noise, and Th = 2 separates these two: the known object is
// accepted from Th = 1.5 on, the stranger rejected up to 3 at least.)
TEST(Server, AcceptsAKnownObjectAndCallsAnUntrainedOneUnknown) {
  ServerProcess server;
  Client client(server.address());
  ASSERT_NO_FATAL_FAILURE(
      EnrollCoilObjects(client, {11, 12, 13}, AzimuthsAwayFrom(60, 90), /*typical=*/true));
  v1::SessionOptions options;
  options.set_rejection(v1::REJECTION_TH);  // the thesis' rule, by name
  options.set_threshold(2.0);
  const auto known = client.Session(options, CoilSweep(12, 60, 10, 4, 0));
  ASSERT_EQ(known.updates.size(), 4u);
  EXPECT_EQ(known.updates.back().candidates(0).name(), "obj12");
  EXPECT_EQ(known.updates.back().decision(), v1::DECISION_ACCEPT);
  // Object 43 was never enrolled; its best match (obj13) scores about 0.13.
  const auto stranger = client.Session(options, CoilSweep(43, 60, 10, 4, 0));
  ASSERT_EQ(stranger.updates.size(), 4u);
  EXPECT_EQ(stranger.updates.back().decision(), v1::DECISION_UNKNOWN);
  // Without typical distances there is nothing to judge by.
  v1::ObjectInfo info;
  ASSERT_TRUE(client.Enroll("obj14", 14, &info).ok());
  ASSERT_TRUE(client.Delete("obj11").ok() && client.Delete("obj12").ok() &&
              client.Delete("obj13").ok());
  const auto untyped = client.Session(options, CoilSweep(14, 60, 10, 2, 0));
  EXPECT_EQ(untyped.updates.back().decision(), v1::DECISION_UNDECIDED);
}

TEST(Server, DeletedObjectDisappearsFromAnOpenSessionAtItsNextFrame) {
  ServerProcess server;
  Client client(server.address());
  ASSERT_NO_FATAL_FAILURE(EnrollCoilObjects(client, {20, 21}));
  grpc::ClientContext context;
  v1::SessionOptions options;
  options.set_top_k(5);
  auto stream = client.OpenSession(context, options);
  v1::SessionUpdate update;
  ASSERT_TRUE(stream->Write(CoilFrame(20, 0, 0)));
  ASSERT_TRUE(stream->Read(&update));
  EXPECT_EQ(update.candidates(0).name(), "obj20");

  ASSERT_TRUE(client.Delete("obj20").ok());
  ASSERT_TRUE(stream->Write(CoilFrame(20, 5, 5)));
  ASSERT_TRUE(stream->Read(&update));
  EXPECT_EQ(update.frame_index(), 1);
  ASSERT_GT(update.candidates_size(), 0);
  for (const auto& c : update.candidates()) EXPECT_NE(c.name(), "obj20");
  stream->WritesDone();
  EXPECT_TRUE(stream->Finish().ok());

  v1::ObjectInfo info;  // and enrolling makes an object appear likewise
  ASSERT_TRUE(client.Enroll("obj20-again", 20, &info).ok());
  const auto after = client.Session(v1::SessionOptions(), {CoilFrame(20, 10, 10)});
  EXPECT_EQ(after.updates.at(0).candidates(0).name(), "obj20-again");
}

TEST(Server, SixteenConcurrentSessionsDoNotCrossTalk) {
  ServerProcess server;
  Client client(server.address());
  std::vector<int> objects;
  for (int i = 0; i < 16; ++i) objects.push_back(30 + i);
  ASSERT_NO_FATAL_FAILURE(EnrollCoilObjects(client, objects, AzimuthsAwayFrom(200, 230)));
  std::vector<std::future<Client::SessionResult>> sessions;
  for (int object : objects) {
    sessions.push_back(std::async(std::launch::async, [&client, object] {
      return client.Session(v1::SessionOptions(), CoilSweep(object, 200, 10, 4, object * 7.0));
    }));
  }
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const auto result = sessions[i].get();
    ASSERT_TRUE(result.status.ok()) << result.status.error_message();
    ASSERT_EQ(result.updates.size(), 4u);
    for (std::size_t k = 0; k < 4; ++k)
      EXPECT_EQ(result.updates[k].frame_index(), static_cast<int>(k));
    EXPECT_EQ(result.updates.back().candidates(0).name(), "obj" + std::to_string(objects[i]));
  }
}

// ---- bad input: the right status, and nothing else harmed ----

v1::SessionRequest FrameWith(std::string cedd, double azimuth, std::string appearance = "") {
  v1::SessionRequest r;
  r.mutable_frame()->set_cedd(std::move(cedd));
  r.mutable_frame()->set_appearance(std::move(appearance));
  r.mutable_frame()->set_azimuth_deg(azimuth);
  return r;
}

TEST(Server, RefusesBadFramesWithInvalidArgumentAndKeepsServing) {
  ServerProcess server;
  Client client(server.address());
  v1::ObjectInfo info;
  ASSERT_TRUE(client.Enroll("obj60", 60, &info).ok());

  // A healthy session runs beside every bad one.
  grpc::ClientContext context;
  auto healthy = client.OpenSession(context);

  const auto [cedd, appearance] = CoilWire(60, 0);
  std::string too_big = cedd;
  too_big[17] = 9;
  v1::SessionOptions full_variant;
  full_variant.set_variant(v1::CEDD_FULL);
  struct Case {
    const char* what;
    v1::SessionOptions options;
    v1::SessionRequest request;
    grpc::StatusCode code;
    const char* message_part;
  } cases[] = {
      {"short descriptor", {}, FrameWith(std::string(100, '\1'), 0), grpc::INVALID_ARGUMENT, "144"},
      {"value out of range", {}, FrameWith(too_big, 0), grpc::INVALID_ARGUMENT, "index 17"},
      {"NaN azimuth",
       {},
       FrameWith(cedd, std::nan(""), appearance),
       grpc::INVALID_ARGUMENT,
       "azimuth"},
      {"infinite azimuth",
       {},
       FrameWith(cedd, std::numeric_limits<double>::infinity(), appearance),
       grpc::INVALID_ARGUMENT,
       "azimuth"},
      {"other variant", full_variant, FrameWith(cedd, 0, appearance), grpc::INVALID_ARGUMENT,
       "cedd-full"},
      {"empty frame", {}, FrameWith("", 0), grpc::INVALID_ARGUMENT, "cedd"},
  };
  for (const Case& c : cases) {
    const auto result = client.Session(c.options, {c.request});
    EXPECT_EQ(result.status.error_code(), c.code)
        << c.what << ": " << result.status.error_message();
    EXPECT_NE(result.status.error_message().find(c.message_part), std::string::npos)
        << c.what << ": " << result.status.error_message();
    EXPECT_TRUE(result.updates.empty()) << c.what;
  }
  // A window outside the API's 1..64 is a bad argument (a window inside it but above the
  // server's --max-window is RESOURCE_EXHAUSTED: tests/server/session_settings_test.cc).
  v1::SessionOptions wide;
  wide.set_window(1000);
  const auto too_wide = client.Session(wide, {});
  EXPECT_EQ(too_wide.status.error_code(), grpc::INVALID_ARGUMENT);
  EXPECT_EQ(too_wide.status.error_message(), "options.window must be in 1..64, got 1000");
  // Any finite azimuth is served, however far apart two frames' are (their difference
  // overflows a double): the HMM session answers both frames.
  v1::SessionOptions hmm;
  hmm.set_engine(v1::ENGINE_HMM);
  const auto far_apart = client.Session(
      hmm, {FrameWith(cedd, 1e308, appearance), FrameWith(cedd, -1e308, appearance)});
  EXPECT_TRUE(far_apart.status.ok()) << far_apart.status.error_message();
  EXPECT_EQ(far_apart.updates.size(), 2u);
  // The HMM's state grows with window x states x objects: 64 x 360 is refused (default limit
  // 1024), 64 x 16 = 1024 is not, and neither is 64 x 360 for an engine without an HMM.
  v1::SessionOptions big_hmm;
  big_hmm.set_engine(v1::ENGINE_HMM);
  big_hmm.set_window(64);
  big_hmm.set_hmm_states(360);
  const auto refused = client.Session(big_hmm, {CoilFrame(60, 35, 35)});
  EXPECT_EQ(refused.status.error_code(), grpc::RESOURCE_EXHAUSTED);
  EXPECT_NE(refused.status.error_message().find("64 x 360"), std::string::npos)
      << refused.status.error_message();
  big_hmm.set_hmm_states(16);
  const auto allowed = client.Session(big_hmm, {CoilFrame(60, 35, 35)});
  EXPECT_TRUE(allowed.status.ok()) << allowed.status.error_message();
  EXPECT_EQ(allowed.updates.size(), 1u);
  big_hmm.set_engine(v1::ENGINE_EIS);
  big_hmm.set_hmm_states(360);
  EXPECT_TRUE(client.Session(big_hmm, {CoilFrame(60, 35, 35)}).status.ok());

  // A frame before `open`.
  {
    grpc::ClientContext ctx;
    client.Prepare(ctx);
    auto stream = client.recognition().Session(&ctx);
    stream->Write(CoilFrame(60, 0, 0));
    stream->WritesDone();
    v1::SessionUpdate ignored;
    while (stream->Read(&ignored)) {
    }
    const grpc::Status s = stream->Finish();
    EXPECT_EQ(s.error_code(), grpc::INVALID_ARGUMENT);
    EXPECT_NE(s.error_message().find("open"), std::string::npos) << s.error_message();
  }

  ASSERT_TRUE(healthy->Write(CoilFrame(60, 35, 35)));
  v1::SessionUpdate update;
  ASSERT_TRUE(healthy->Read(&update));
  EXPECT_EQ(update.frame_index(), 0);
  EXPECT_EQ(update.candidates(0).name(), "obj60");
  healthy->WritesDone();
  EXPECT_TRUE(healthy->Finish().ok());
  EXPECT_GT(server.pid(), 0);
}

TEST(Server, RefusesBadModelRequests) {
  ServerProcess server;
  Client client(server.address());
  v1::ObjectInfo info;
  ASSERT_TRUE(client.Enroll("obj61", 61, &info, {0, 90}).ok());
  EXPECT_EQ(client.Enroll("obj61", 62, &info, {0}).error_code(), grpc::ALREADY_EXISTS);
  EXPECT_EQ(client.Enroll("bad name!", 62, &info, {0}).error_code(), grpc::INVALID_ARGUMENT);
  EXPECT_EQ(client.Delete("no-such-object").error_code(), grpc::NOT_FOUND);

  std::vector<v1::EnrollRequest> no_views(1);
  no_views[0].mutable_header()->set_name("empty");
  EXPECT_EQ(client.EnrollRaw(no_views, &info).error_code(), grpc::INVALID_ARGUMENT);
  std::vector<v1::EnrollRequest> no_header(1);
  SetCoilDescriptor(no_header[0].mutable_view(), 61, 0);
  EXPECT_EQ(client.EnrollRaw(no_header, &info).error_code(), grpc::INVALID_ARGUMENT);
  std::vector<v1::EnrollRequest> bad_view(2);
  bad_view[0].mutable_header()->set_name("bad-view");
  bad_view[1].mutable_view()->set_cedd("short");
  EXPECT_EQ(client.EnrollRaw(bad_view, &info).error_code(), grpc::INVALID_ARGUMENT);

  // Nothing of the refused enrollments was stored.
  v1::ListObjectsResponse list;
  ASSERT_TRUE(client.List(&list).ok());
  ASSERT_EQ(list.objects_size(), 1);
  EXPECT_EQ(list.objects(0).name(), "obj61");
  EXPECT_EQ(list.objects(0).view_count(), 2);
}

TEST(Server, LimitsSessionsAndFrameRateWithResourceExhausted) {
  ServerProcess server({.extra_args = {"--max-sessions", "2", "--max-fps", "2"}});
  Client client(server.address());
  v1::ObjectInfo info;
  ASSERT_TRUE(client.Enroll("obj70", 70, &info, {0, 45, 90}).ok());

  // Two sessions held open; the third is refused.
  std::vector<std::unique_ptr<grpc::ClientContext>> contexts;
  std::vector<std::unique_ptr<Client::SessionStream>> open;
  for (int i = 0; i < 2; ++i) {
    contexts.push_back(std::make_unique<grpc::ClientContext>());
    open.push_back(client.OpenSession(*contexts.back()));
    ASSERT_TRUE(open.back()->Write(CoilFrame(70, 0, 0)));
    v1::SessionUpdate u;
    ASSERT_TRUE(open.back()->Read(&u));  // the session is certainly registered now
  }
  const auto third = client.Session(v1::SessionOptions(), {CoilFrame(70, 0, 0)});
  EXPECT_EQ(third.status.error_code(), grpc::RESOURCE_EXHAUSTED) << third.status.error_message();

  // 2 frames/s with a 2-second allowance: the 5th frame sent at once is over the limit.
  v1::SessionUpdate u;
  for (int k = 0; k < 3; ++k) {
    ASSERT_TRUE(open[0]->Write(CoilFrame(70, 45, 45)));
    ASSERT_TRUE(open[0]->Read(&u));
  }
  open[0]->Write(CoilFrame(70, 90, 90));
  EXPECT_FALSE(open[0]->Read(&u));
  const grpc::Status limited = open[0]->Finish();
  EXPECT_EQ(limited.error_code(), grpc::RESOURCE_EXHAUSTED) << limited.error_message();

  // The other session is unaffected.
  ASSERT_TRUE(open[1]->Write(CoilFrame(70, 45, 45)));
  ASSERT_TRUE(open[1]->Read(&u));
  EXPECT_EQ(u.frame_index(), 1);
  open[1]->WritesDone();
  EXPECT_TRUE(open[1]->Finish().ok());
}

TEST(Server, RefusesOversizedMessagesWithResourceExhausted) {
  ServerProcess server({.extra_args = {"--max-message-bytes", "65536"}});
  Client client(server.address());
  v1::ObjectInfo info;
  ASSERT_TRUE(client.Enroll("obj71", 71, &info, {0, 90}).ok());
  v1::SessionRequest huge;
  huge.mutable_frame()->set_image(std::string(100000, 'x'));
  huge.mutable_frame()->set_azimuth_deg(0);
  const auto result = client.Session(v1::SessionOptions(), {huge});
  EXPECT_EQ(result.status.error_code(), grpc::RESOURCE_EXHAUSTED) << result.status.error_message();
  // The server carries on.
  const auto next = client.Session(v1::SessionOptions(), {CoilFrame(71, 0, 0)});
  ASSERT_TRUE(next.status.ok()) << next.status.error_message();
  EXPECT_EQ(next.updates.at(0).candidates(0).name(), "obj71");
}

TEST(Server, ClosesIdleSessionsWithDeadlineExceeded) {
  ServerProcess server({.extra_args = {"--idle-timeout", "1"}});
  Client client(server.address());
  grpc::ClientContext context;
  auto stream = client.OpenSession(context);
  v1::SessionUpdate u;
  EXPECT_FALSE(stream->Read(&u));  // returns when the server ends the stream
  const grpc::Status s = stream->Finish();
  EXPECT_EQ(s.error_code(), grpc::DEADLINE_EXCEEDED) << s.error_message();
  EXPECT_NE(s.error_message().find("without a frame"), std::string::npos);
}

// ---- access control, TLS ----

TEST(Server, TokensGrantRoles) {
  const auto tokens =
      std::filesystem::temp_directory_path() / ("orbit_tokens_" + std::to_string(getpid()));
  testing::WriteTokenFile(tokens,
                          "# operators\nadmin-token-0123456789 admin\n"
                          "device-token-0123456789 recognize\n");
  ServerProcess server({.tokens_file = tokens});
  v1::ObjectInfo info;
  v1::ListObjectsResponse list;

  const Client anonymous(server.address());
  EXPECT_EQ(anonymous.List(&list).error_code(), grpc::UNAUTHENTICATED);
  EXPECT_EQ(anonymous.Session(v1::SessionOptions(), {}).status.error_code(), grpc::UNAUTHENTICATED);
  const Client stranger(server.address(), "not-a-known-token-at-all");
  EXPECT_EQ(stranger.List(&list).error_code(), grpc::UNAUTHENTICATED);

  const Client device(server.address(), "device-token-0123456789");
  EXPECT_EQ(device.Enroll("obj80", 80, &info, {0}).error_code(), grpc::PERMISSION_DENIED);
  const Client admin(server.address(), "admin-token-0123456789");
  ASSERT_TRUE(admin.Enroll("obj80", 80, &info, {0, 90}).ok());
  EXPECT_EQ(device.Delete("obj80").error_code(), grpc::PERMISSION_DENIED);

  ASSERT_TRUE(device.List(&list).ok());
  EXPECT_EQ(list.objects_size(), 1);
  const auto session = device.Session(v1::SessionOptions(), {CoilFrame(80, 0, 0)});
  EXPECT_TRUE(session.status.ok()) << session.status.error_message();
  EXPECT_EQ(session.updates.size(), 1u);
  std::filesystem::remove(tokens);
}

// Tokens rotated while serving: a SIGHUP reads the file again, the revoked token's session ends
// with UNAUTHENTICATED at once while another token's carries on; an edit without a signal is read
// within seconds; and every administrative call, and every refused token, is one JSON line of the
// audit log naming the token, the call, the object and the outcome.
TEST(Server, RotatesTokensWhileServingAndAuditsEveryAdministrativeCall) {
  testing::ScratchDir dir;
  const auto tokens = dir / "tokens";
  const auto audit = dir / "audit.jsonl";
  const std::string admin = "admin-token-0123456789", phone = "phone-token-0123456789",
                    drone = "drone-token-0123456789";
  using server::Role;
  using server::TokenFileLine;
  testing::WriteTokenFile(tokens, TokenFileLine("ops", Role::kAdmin, admin) + "\n" +
                                      TokenFileLine("phone", Role::kRecognize, phone) + "\n" +
                                      TokenFileLine("drone", Role::kRecognize, drone) + "\n");
  ServerProcess server({.tokens_file = tokens, .extra_args = {"--audit-log", audit.string()}});
  v1::ObjectInfo info;
  ASSERT_TRUE(Client(server.address(), admin).Enroll("obj80", 80, &info, {0, 90}).ok());

  Client phone_client(server.address(), phone), drone_client(server.address(), drone);
  grpc::ClientContext phone_context, drone_context;
  auto phone_stream = phone_client.OpenSession(phone_context);
  auto drone_stream = drone_client.OpenSession(drone_context);
  v1::SessionUpdate update;
  ASSERT_TRUE(phone_stream->Write(CoilFrame(80, 0, 0)) && phone_stream->Read(&update));
  ASSERT_TRUE(drone_stream->Write(CoilFrame(80, 0, 0)) && drone_stream->Read(&update));

  // The phone's token is revoked: it is no longer in the file.
  testing::WriteTokenFile(tokens, TokenFileLine("ops", Role::kAdmin, admin) + "\n" +
                                      TokenFileLine("drone", Role::kRecognize, drone) + "\n");
  kill(server.pid(), SIGHUP);
  EXPECT_FALSE(phone_stream->Read(&update));
  const grpc::Status ended = phone_stream->Finish();
  EXPECT_EQ(ended.error_code(), grpc::UNAUTHENTICATED) << ended.error_message();
  EXPECT_EQ(ended.error_message(), "the token of this stream was revoked");
  EXPECT_TRUE(drone_stream->Write(CoilFrame(80, 90, 90)) && drone_stream->Read(&update))
      << "another token's session carries on";
  v1::ListObjectsResponse list;
  EXPECT_EQ(phone_client.List(&list).error_code(), grpc::UNAUTHENTICATED);

  // An edit without a signal: the drone's token is revoked within a few seconds.
  testing::WriteTokenFile(tokens, TokenFileLine("ops", Role::kAdmin, admin) + "\n");
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (drone_client.List(&list).ok() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  EXPECT_EQ(drone_client.List(&list).error_code(), grpc::UNAUTHENTICATED);
  drone_stream->WritesDone();
  EXPECT_EQ(drone_stream->Finish().error_code(), grpc::UNAUTHENTICATED);

  ASSERT_TRUE(Client(server.address(), admin).Delete("obj80").ok());
  EXPECT_NE(server.Log().find("tokens reloaded from " + tokens.string() +
                              ": 2 in force; "
                              "revoked: phone"),
            std::string::npos)
      << server.Log();

  std::ifstream in(audit);
  std::vector<nlohmann::json> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(nlohmann::json::parse(line));
  const auto has = [&lines](const std::string& call, const std::string& token,
                            const std::string& object, const std::string& outcome) {
    return std::any_of(lines.begin(), lines.end(), [&](const nlohmann::json& line) {
      return line["call"] == call && line["token"] == token && line["object"] == object &&
             line["outcome"] == outcome &&
             line["peer"].get<std::string>().rfind("ipv4:127.0.0.1:", 0) == 0;
    });
  };
  EXPECT_TRUE(has("Models/Enroll", "ops", "obj80", "OK"));
  EXPECT_TRUE(has("Models/DeleteObject", "ops", "obj80", "OK"));
  EXPECT_TRUE(has("Models/ListObjects", "", "", "UNAUTHENTICATED"));
  for (const nlohmann::json& line : lines) {
    EXPECT_EQ(line.dump().find(admin), std::string::npos) << "no token is ever written";
  }
}

// Tokens over plain text on an address others can reach: served (a proxy may terminate TLS in
// front), with a warning that says what is at stake and what to do.
TEST(Server, WarnsThatTokensTravelInClearTextOffLoopbackWithoutTls) {
  testing::ScratchDir dir;
  testing::WriteTokenFile(
      dir / "tokens",
      server::TokenFileLine("ops", server::Role::kAdmin, "admin-token-0123456789") + "\n");
  ServerProcess remote({.listen = "0.0.0.0:0", .tokens_file = dir / "tokens"});
  EXPECT_NE(remote.Log().find("warning: tokens on 0.0.0.0:0 travel in clear text"),
            std::string::npos)
      << remote.Log();
  ServerProcess local({.tokens_file = dir / "tokens"});
  EXPECT_EQ(local.Log().find("clear text"), std::string::npos) << local.Log();
}

TEST(Server, RefusesToServeARemoteAddressWithoutTokens) {
  const auto refused = testing::StartServerExpectingRefusal(
      {"serve", "--db", (std::filesystem::temp_directory_path() / "orbit_refused.db").string(),
       "--listen", "0.0.0.0:0"});
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.log.find("without tokens"), std::string::npos) << refused.log;
  std::filesystem::remove(std::filesystem::temp_directory_path() / "orbit_refused.db");
}

TEST(Server, ServesTlsWithACertificate) {
  const testing::ScratchDir scratch;
  const std::filesystem::path& dir = scratch.path();
  testing::MakeSelfSignedCertificate(dir, "localhost", "DNS:localhost,IP:127.0.0.1");
  ServerProcess server({.tls_cert = dir / "cert.pem", .tls_key = dir / "key.pem"});

  std::ifstream cert_file(dir / "cert.pem");
  std::stringstream cert;
  cert << cert_file.rdbuf();
  grpc::SslCredentialsOptions ssl;
  ssl.pem_root_certs = cert.str();
  const Client secure("localhost:" + std::to_string(server.port()), "", grpc::SslCredentials(ssl));
  v1::ObjectInfo info;
  ASSERT_TRUE(secure.Enroll("obj81", 81, &info, {0, 180}).ok());

  const Client plain(server.address());  // plaintext against TLS: the call fails
  v1::ListObjectsResponse list;
  EXPECT_EQ(plain.List(&list).error_code(), grpc::UNAVAILABLE);
}

// ---- durability and shutdown ----

TEST(Server, AcknowledgedEnrollmentSurvivesKillNine) {
  const testing::ScratchDir scratch;
  const std::filesystem::path& dir = scratch.path();
  const auto db = dir / "models.db";
  int port = 0;
  {
    ServerProcess server({.database = db});
    port = server.port();
    Client client(server.address());
    v1::ObjectInfo info;
    ASSERT_TRUE(client.Enroll("obj90", 90, &info).ok());
    EXPECT_EQ(server.Stop(SIGKILL), 128 + SIGKILL);
  }
  ServerProcess restarted({.database = db, .listen = "127.0.0.1:" + std::to_string(port)});
  Client client(restarted.address());
  v1::ListObjectsResponse list;
  ASSERT_TRUE(client.List(&list).ok());
  ASSERT_EQ(list.objects_size(), 1);
  EXPECT_EQ(list.objects(0).view_count(), 72);
  const auto session = client.Session(v1::SessionOptions(), {CoilFrame(90, 45, 0)});
  EXPECT_EQ(session.updates.at(0).candidates(0).name(), "obj90");
}

// ---- a PostgreSQL store shared by servers ----

TEST(Server, PostgresStoreIsSharedByServersStartedOnIt) {
  const testing::TestDatabase database;
  ServerProcess first({.store = database.conninfo()});
  v1::ObjectInfo info;
  ASSERT_TRUE(Client(first.address()).Enroll("obj92", 92, &info).ok());

  ServerProcess second({.store = database.conninfo()});  // indexes what the first stored
  Client client(second.address());
  v1::ListObjectsResponse list;
  ASSERT_TRUE(client.List(&list).ok());
  ASSERT_EQ(list.objects_size(), 1);
  EXPECT_EQ(list.objects(0).view_count(), 72);
  const auto session = client.Session(v1::SessionOptions(), {CoilFrame(92, 45, 0)});
  ASSERT_TRUE(session.status.ok()) << session.status.error_message();
  EXPECT_EQ(session.updates.at(0).candidates(0).name(), "obj92");
  EXPECT_NE(
      second.Log().find("model store         PostgreSQL user=orbit dbname=" + database.name()),
      std::string::npos)
      << second.Log();
}

// A server listens before it has loaded its index: while it loads, health says NOT_SERVING (a
// balancer keeps sessions away) and Orbit calls get UNAVAILABLE naming the reason; then SERVING.
// The load is held up by a test transaction locking the views table (for less than the store's
// 5 s lock timeout).
TEST(Server, PostgresReplicaIsNotServingUntilItHasLoadedItsIndex) {
  const testing::TestDatabase database;
  {
    ServerProcess first({.store = database.conninfo()});
    v1::ObjectInfo info;
    ASSERT_TRUE(Client(first.address()).Enroll("obj92", 92, &info).ok());
  }
  PostgresConnection locker(database.conninfo(), 0);
  locker.Execute("BEGIN; LOCK TABLE views IN ACCESS EXCLUSIVE MODE");
  const std::string address = "127.0.0.1:" + std::to_string(testing::FreeLoopbackPort());
  auto starting = std::async(std::launch::async, [&] {
    // The variant given: finding the store's own would read the locked table before listening.
    return std::make_unique<ServerProcess>(ServerProcessOptions{
        .store = database.conninfo(),
        .listen = address,
        .extra_args = {"--variant", std::string(VariantName(Product().variant))}});
  });
  std::optional<int> health;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(3);
  while (!(health = testing::HealthStatus(address)) &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_EQ(health, testing::kNotServing);
  EXPECT_EQ(testing::HealthStatus(address, "orbit.v1.Recognition"), testing::kNotServing);
  Client client(address);
  v1::ListObjectsResponse list;
  const grpc::Status refused = client.List(&list);
  EXPECT_EQ(refused.error_code(), grpc::StatusCode::UNAVAILABLE);
  EXPECT_NE(refused.error_message().find("loading its model index"), std::string::npos)
      << refused.error_message();
  const auto session = client.Session(v1::SessionOptions(), {CoilFrame(92, 45, 0)});
  EXPECT_EQ(session.status.error_code(), grpc::StatusCode::UNAVAILABLE);

  locker.Execute("COMMIT");
  const std::unique_ptr<ServerProcess> server = starting.get();
  EXPECT_EQ(testing::HealthStatus(address), testing::kServing);
  const auto recognised = client.Session(v1::SessionOptions(), {CoilFrame(92, 45, 0)});
  ASSERT_TRUE(recognised.status.ok()) << recognised.status.error_message();
  EXPECT_EQ(recognised.updates.at(0).candidates(0).name(), "obj92");
}

// SIGTERM while the server loads its store ends it at once, without waiting for the load (the
// load is held up, as above, by a transaction locking the views table); the store is intact.
TEST(Server, PostgresReplicaStopsAtOnceWhileItLoads) {
  const testing::TestDatabase database;
  {
    ServerProcess first({.store = database.conninfo()});
    v1::ObjectInfo info;
    ASSERT_TRUE(Client(first.address()).Enroll("obj92", 92, &info).ok());
  }
  const std::string address = "127.0.0.1:" + std::to_string(testing::FreeLoopbackPort());
  {
    PostgresConnection locker(database.conninfo(), 0);
    locker.Execute("BEGIN; LOCK TABLE views IN ACCESS EXCLUSIVE MODE");
    ServerProcess loading({.store = database.conninfo(),
                           .listen = address,
                           .extra_args = {"--variant", std::string(VariantName(Product().variant))},
                           .wait_until = ServerProcessOptions::Until::kLoading});
    std::optional<int> health;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(3);
    while (!(health = testing::HealthStatus(address)) &&
           std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    ASSERT_EQ(health, testing::kNotServing) << loading.Log();
    const auto sent = std::chrono::steady_clock::now();
    EXPECT_EQ(loading.Stop(SIGTERM, std::chrono::seconds(4)), 0) << loading.Log();
    // Well before the store's 5 s lock timeout would have ended the load.
    EXPECT_LT(std::chrono::steady_clock::now() - sent, std::chrono::seconds(2));
    EXPECT_NE(loading.Log().find("SIGTERM while loading the store: stopped before serving"),
              std::string::npos)
        << loading.Log();
    EXPECT_EQ(loading.Log().find("listening on"), std::string::npos) << loading.Log();
    locker.Execute("COMMIT");
  }
  ServerProcess again({.store = database.conninfo()});
  Client client(again.address());
  const auto session = client.Session(v1::SessionOptions(), {CoilFrame(92, 45, 0)});
  ASSERT_TRUE(session.status.ok()) << session.status.error_message();
  EXPECT_EQ(session.updates.at(0).candidates(0).name(), "obj92");
}

TEST(Server, PostgresStoreOutOfReachStopsTheStartWithAClearMessage) {
  const testing::ScratchDir scratch;  // no server's socket in it
  const std::string store = "postgresql://orbit:s3cret@/models?host=" + scratch.path().string();
  const auto refused =
      testing::StartServerExpectingRefusal({"serve", "--store", store, "--listen", "127.0.0.1:0"});
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_NE(refused.log.find("cannot connect to PostgreSQL"), std::string::npos) << refused.log;
  EXPECT_NE(refused.log.find("host=" + scratch.path().string()), std::string::npos);
  EXPECT_EQ(refused.log.find("s3cret"), std::string::npos) << refused.log;

  const auto both = testing::StartServerExpectingRefusal(
      {"serve", "--store", store, "--db", (scratch.path() / "models.db").string()});
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_NE(both.log.find("--db FILE (SQLite) or --store"), std::string::npos) << both.log;
}

TEST(Server, HalfSentEnrollmentLeavesNothing) {
  ServerProcess server;
  Client client(server.address());
  {
    grpc::ClientContext context;
    client.Prepare(context);
    v1::ObjectInfo info;
    auto writer = client.models_for_test(&context, &info);
    v1::EnrollRequest header;
    header.mutable_header()->set_name("half");
    ASSERT_TRUE(writer->Write(header));
    v1::EnrollRequest view;
    SetCoilDescriptor(view.mutable_view(), 91, 0);
    ASSERT_TRUE(writer->Write(view));
    context.TryCancel();  // the connection breaks before the stream ends
    EXPECT_FALSE(writer->Finish().ok());
  }
  v1::ListObjectsResponse list;
  ASSERT_TRUE(client.List(&list).ok());
  EXPECT_EQ(list.objects_size(), 0);
}

TEST(Server, SigtermEndsOpenSessionsCleanlyAndExitsZero) {
  ServerProcess server;
  Client client(server.address());
  grpc::ClientContext context;
  auto stream = client.OpenSession(context);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // the session is open
  auto exit_code = std::async(std::launch::async, [&server] { return server.Stop(SIGTERM); });
  v1::SessionUpdate u;
  EXPECT_FALSE(stream->Read(&u));
  const grpc::Status s = stream->Finish();
  EXPECT_EQ(s.error_code(), grpc::UNAVAILABLE) << s.error_message();
  EXPECT_EQ(exit_code.get(), 0);
}

// A bomb: an image whose header claims 30000x30000 pixels (2.7 GB decoded) in 18 KB is
// refused from its header, before any decoding, and the server carries on.
TEST(Server, RefusesADecompressionBombFromItsHeaderAndKeepsServing) {
  ServerProcess server;
  EXPECT_NE(server.Log().find("images <= 16777216 pixels"), std::string::npos) << server.Log();
  Client client(server.address());
  v1::ObjectInfo info;
  ASSERT_TRUE(client.Enroll("obj9", 9, &info).ok());

  // A real 128x128 COIL-100 PNG whose header (IHDR, CRC fixed) claims 30000x30000.
  std::ifstream file(testing::DataDir() / "coil-100" / "obj9__30.png", std::ios::binary);
  const std::string png((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  ASSERT_GT(png.size(), 33u);
  std::string bomb = png;
  for (int field : {16, 20}) {  // width, height
    for (int i = 0; i < 4; ++i) bomb[field + i] = static_cast<char>(30000 >> (24 - 8 * i));
  }
  const auto crc = crc32(0, reinterpret_cast<const Bytef*>(bomb.data() + 12), 4 + 13);
  for (int i = 0; i < 4; ++i) bomb[29 + i] = static_cast<char>(crc >> (24 - 8 * i));

  v1::SessionRequest bomb_frame;
  bomb_frame.mutable_frame()->set_image(bomb);
  bomb_frame.mutable_frame()->set_azimuth_deg(30);
  const auto refused = client.Session(v1::SessionOptions(), {bomb_frame});
  EXPECT_EQ(refused.status.error_code(), grpc::RESOURCE_EXHAUSTED)
      << refused.status.error_message();
  EXPECT_EQ(refused.status.error_message(),
            "frame.image is 30000x30000 pixels; at most 16777216 pixels (4096x4096) are decoded");
  EXPECT_TRUE(refused.updates.empty());

  // Another session on the same server is answered, from the genuine image.
  v1::SessionRequest frame = bomb_frame;
  frame.mutable_frame()->set_image(png);
  const auto answered = client.Session(v1::SessionOptions(), {frame});
  ASSERT_TRUE(answered.status.ok()) << answered.status.error_message();
  ASSERT_EQ(answered.updates.size(), 1u);
  EXPECT_EQ(answered.updates[0].candidates(0).name(), "obj9");
}

}  // namespace
}  // namespace orbit
