// The replicated deployment of docker/: `orbit serve` replicas on one PostgreSQL store behind
// HAProxy running docker/haproxy.cfg, all real processes on loopback. What a user of it must be
// able to count on: an object enrolled through one replica is recognised on the others; a
// session survives the loss of its replica; a replica killed mid-enrollment leaves nothing half
// done; replicas ride out a restart of the database.
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "client/connection.h"
#include "client/enroller.h"
#include "client/models_client.h"
#include "client/recognition_session.h"
#include "tests/support/balancer_process.h"
#include "tests/support/client_test_support.h"
#include "tests/support/http_client.h"
#include "tests/support/postgres_test_cluster.h"
#include "tests/support/server_process.h"
#include "tests/support/storage_test_support.h"
#include "tests/support/wait_until.h"

namespace orbit {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;
using testing::At;
using testing::BalancerProcess;
using testing::CoilImage;
using testing::ServerProcess;
using testing::ServerProcessOptions;
using testing::TestDatabase;
using testing::WaitUntil;

ServerProcessOptions Replica(const std::string& conninfo) {
  return {.store = conninfo, .metrics = true};
}

// A gauge of the replica's /metrics, e.g. orbit_open_sessions.
double Gauge(const ServerProcess& replica, const std::string& name) {
  const std::string body = testing::HttpRequest(replica.metrics_address(), "GET", "/metrics").body;
  std::smatch match;
  if (!std::regex_search(body, match, std::regex("\n" + name + " ([0-9.e+]+)"))) return -1;
  return std::stod(match[1]);
}

// The names of the objects `replica` serves.
std::vector<std::string> Names(const std::string& address) {
  const Connection connection(At(address));
  std::vector<std::string> names;
  for (const v1::ObjectInfo& object : ModelsClient(connection).ListAllObjects()) {
    names.push_back(object.name());
  }
  return names;
}

// A sweep of `object` from 105 degrees in 10-degree steps (never an enrolled view).
std::int64_t PushSweepFrame(RecognitionSession& session, int object, int k) {
  return session.Push(CoilImage(object, 105 + 10 * k), 105 + 10 * k);
}

TEST(PostgresReplicasTest, AnObjectEnrolledThroughOneReplicaIsRecognisedOnTheOther) {
  TestDatabase database;
  ServerProcess a(Replica(database.conninfo()));
  ServerProcess b(Replica(database.conninfo()));
  BalancerProcess balancer({a.address(), b.address()});

  const Clock::time_point enrolled_at = Clock::now();
  testing::EnrollCoilObjects(Connection(At(a.address())), 1, 3);
  ASSERT_TRUE(WaitUntil([&] { return Gauge(b, "orbit_index_objects") == 3; })) << b.Log();
  std::cout << "replica B serves A's 3 enrollments "
            << std::chrono::duration<double>(Clock::now() - enrolled_at).count()
            << " s after A began them\n";
  // B measured each one's delay from A's commit; A, whose own changes they are, none.
  ASSERT_TRUE(WaitUntil([&] { return Gauge(b, "orbit_model_change_lag_seconds_count") == 3; }));
  const double mean_lag = Gauge(b, "orbit_model_change_lag_seconds_sum") / 3;
  EXPECT_GE(mean_lag, 0);
  EXPECT_LT(mean_lag, 10);
  std::cout << "mean delay from A's commit to B's index: " << mean_lag * 1000 << " ms\n";
  EXPECT_EQ(Gauge(a, "orbit_model_change_lag_seconds_count"), 0);

  // Two sessions through the balancer: one on each replica (the fewest streams gets the next),
  // and each recognises the object.
  const Connection through(At(balancer.address()));
  auto first = RecognitionSession::Open(through, testing::TopK(3));
  PushSweepFrame(*first, 2, 0);
  ASSERT_TRUE(first->NextUpdate().has_value());
  auto second = RecognitionSession::Open(through, testing::TopK(3));
  PushSweepFrame(*second, 2, 0);
  ASSERT_TRUE(second->NextUpdate().has_value());
  EXPECT_EQ(Gauge(a, "orbit_open_sessions"), 1);
  EXPECT_EQ(Gauge(b, "orbit_open_sessions"), 1);
  for (RecognitionSession* session : {first.get(), second.get()}) {
    std::optional<v1::SessionUpdate> last;
    for (int k = 1; k < 6; ++k) PushSweepFrame(*session, 2, k);
    for (int k = 1; k < 6; ++k) last = session->NextUpdate();
    ASSERT_TRUE(last.has_value());
    EXPECT_EQ(last->candidates(0).name(), "obj2");
    EXPECT_TRUE(session->Close().ok());
  }

  // Deleting works the same way.
  const Connection at_b(At(b.address()));
  v1::ObjectRef obj1;
  obj1.set_name("obj1");
  ModelsClient(at_b).DeleteObject(obj1);
  ASSERT_TRUE(WaitUntil([&] { return Gauge(a, "orbit_index_objects") == 2; })) << a.Log();
  EXPECT_EQ(Gauge(a, "orbit_model_change_lag_seconds_count"), 1);
}

TEST(PostgresReplicasTest, ASessionSurvivesTheLossOfItsReplica) {
  constexpr int kObject = 3;
  TestDatabase database;
  ServerProcess a(Replica(database.conninfo()));
  ServerProcess b(Replica(database.conninfo()));
  BalancerProcess balancer({a.address(), b.address()});
  const Connection through(At(balancer.address()));
  testing::EnrollCoilObjects(through, 1, 5);
  ASSERT_TRUE(WaitUntil([&] {
    return Gauge(a, "orbit_index_objects") == 5 && Gauge(b, "orbit_index_objects") == 5;
  }));

  auto session = RecognitionSession::Open(through, testing::TopK(3));
  for (int k = 0; k < 5; ++k) PushSweepFrame(*session, kObject, k);
  std::vector<v1::SessionUpdate> updates;
  for (int k = 0; k < 5; ++k) updates.push_back(*session->NextUpdate());
  ServerProcess& holder = Gauge(a, "orbit_open_sessions") == 1 ? a : b;
  ServerProcess& survivor = &holder == &a ? b : a;
  ASSERT_EQ(Gauge(holder, "orbit_open_sessions"), 1);

  ASSERT_EQ(holder.Stop(SIGKILL), 128 + SIGKILL);
  for (int k = 5; k < 10; ++k) PushSweepFrame(*session, kObject, k);
  for (int k = 5; k < 10; ++k) {
    std::optional<v1::SessionUpdate> update = session->NextUpdate();
    ASSERT_TRUE(update.has_value()) << session->Close().error_message() << "\n" << balancer.Log();
    updates.push_back(*update);
  }
  EXPECT_GE(session->reconnections(), 1);
  EXPECT_EQ(Gauge(survivor, "orbit_open_sessions"), 1);
  ASSERT_TRUE(session->Close().ok());
  // Every frame answered once, in order, and the replayed window carried the evidence over.
  for (int k = 0; k < 10; ++k) EXPECT_EQ(updates[k].frame_index(), k);
  EXPECT_EQ(updates.back().candidates(0).name(), "obj3");
}

TEST(PostgresReplicasTest, AReplicaKilledMidEnrollmentLeavesNothingOnTheOther) {
  TestDatabase database;
  ServerProcess a(Replica(database.conninfo()));
  ServerProcess b(Replica(database.conninfo()));
  const Connection at_a(At(a.address()));
  const std::vector<v1::View> views = Enroller(at_a).ComputeViews(testing::CoilEnrollmentImages(7));

  // Half of the views sent, the stream still open: then A dies.
  auto stub = v1::Models::NewStub(at_a.channel());
  grpc::ClientContext context;
  v1::ObjectInfo reply;
  auto stream = stub->Enroll(&context, &reply);
  v1::EnrollRequest header;
  header.mutable_header()->set_name("obj7");
  ASSERT_TRUE(stream->Write(header));
  for (std::size_t f = 0; f < views.size() / 2; ++f) {
    v1::EnrollRequest request;
    *request.mutable_view() = views[f];
    ASSERT_TRUE(stream->Write(request));
  }
  ASSERT_EQ(a.Stop(SIGKILL), 128 + SIGKILL);
  EXPECT_FALSE(stream->Finish().ok());

  // B learns of an enrollment through it meanwhile, and of nothing from A.
  testing::EnrollCoilObjects(Connection(At(b.address())), 1, 1);
  ASSERT_TRUE(WaitUntil([&] { return Gauge(b, "orbit_index_objects") == 1; }));
  std::this_thread::sleep_for(milliseconds(1500));  // a full poll interval of B's follower
  EXPECT_EQ(Names(b.address()), std::vector<std::string>{"obj1"});
  EXPECT_EQ(database.Int("SELECT count(*) FROM objects"), 1);
  EXPECT_EQ(database.Int("SELECT count(*) FROM views"),
            static_cast<std::int64_t>(testing::CoilEnrollmentImages(1).size()));
}

// PostgreSQL restarts under two replicas: they keep serving what they have, report NOT_SERVING
// after their grace (the balancer takes them out), and once it is back they catch up with an
// enrollment made through the other and are put back. On a private PostgreSQL server: the
// shared one serves other tests meanwhile.
TEST(PostgresReplicasTest, ReplicasRideOutARestartOfTheDatabase) {
  const testing::PrivatePostgresServer database;
  ServerProcessOptions options = Replica(database.conninfo());
  options.extra_args = {"--store-grace", "1"};
  ServerProcess a(options);
  ServerProcess b(options);
  BalancerProcess balancer({a.address(), b.address()});
  testing::EnrollCoilObjects(Connection(At(a.address())), 1, 2);
  ASSERT_TRUE(WaitUntil([&] { return Gauge(b, "orbit_index_objects") == 2; }));

  database.Crash();
  EXPECT_TRUE(balancer.WaitUntilDown(1, milliseconds(15000))) << balancer.Log();
  EXPECT_TRUE(balancer.WaitUntilDown(2, milliseconds(15000))) << balancer.Log();
  // B still recognises with the models it has (only listing reads the store).
  auto session = RecognitionSession::Open(Connection(At(b.address())), testing::TopK(3));
  std::optional<v1::SessionUpdate> last;
  for (int k = 0; k < 4; ++k) PushSweepFrame(*session, 2, k);
  for (int k = 0; k < 4; ++k) last = session->NextUpdate();
  ASSERT_TRUE(last.has_value());
  EXPECT_EQ(last->candidates(0).name(), "obj2");
  EXPECT_TRUE(session->Close().ok());

  database.Restart();
  EXPECT_TRUE(balancer.WaitUntilUp(1, milliseconds(15000))) << balancer.Log();
  EXPECT_TRUE(balancer.WaitUntilUp(2, milliseconds(15000))) << balancer.Log();
  testing::EnrollCoilObjects(Connection(At(a.address())), 3, 3);
  ASSERT_TRUE(WaitUntil([&] { return Gauge(b, "orbit_index_objects") == 3; })) << b.Log();
  EXPECT_NE(b.Log().find("the model store answers again"), std::string::npos) << b.Log();
}

}  // namespace
}  // namespace orbit
