// The open recognition sessions: the limit on their number, the idle timeout and the end at
// shutdown (server/session_registry.h; docs/design.md#service-behaviour). The sessions are a
// small implementation of RegisteredSession that records how it was closed.
#include "server/session_registry.h"

#include <chrono>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace orbit::server {
namespace {

using std::chrono::seconds;
using std::chrono::steady_clock;
using ::testing::HasSubstr;

// A session that only records the statuses it was closed with. Like a real session it stays
// registered after Close until it removes itself.
class RecordingSession : public RegisteredSession {
 public:
  explicit RecordingSession(steady_clock::time_point last_activity = steady_clock::now())
      : last_activity_(last_activity) {}

  void Close(const grpc::Status& status) override { closed_with_.push_back(status); }
  steady_clock::time_point last_activity() const override { return last_activity_; }

  const std::vector<grpc::Status>& closed_with() const { return closed_with_; }

 private:
  steady_clock::time_point last_activity_;
  std::vector<grpc::Status> closed_with_;
};

TEST(SessionRegistryTest, CountsTheSessionsAddedAndNotYetRemoved) {
  SessionRegistry registry({.max_open = 8});
  RecordingSession a, b, c;
  EXPECT_EQ(registry.size(), 0);
  ASSERT_TRUE(registry.Add(&a).ok());
  ASSERT_TRUE(registry.Add(&b).ok());
  ASSERT_TRUE(registry.Add(&c).ok());
  EXPECT_EQ(registry.size(), 3);
  registry.Remove(&b);
  EXPECT_EQ(registry.size(), 2);
  registry.Remove(&a);
  registry.Remove(&c);
  EXPECT_EQ(registry.size(), 0);
}

TEST(SessionRegistryTest, RefusesSessionsBeyondTheMaximumUntilOneLeaves) {
  SessionRegistry registry({.max_open = 2});
  RecordingSession a, b, c;
  ASSERT_TRUE(registry.Add(&a).ok());
  ASSERT_TRUE(registry.Add(&b).ok());

  const grpc::Status refused = registry.Add(&c);
  EXPECT_EQ(refused.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_THAT(refused.error_message(), HasSubstr("maximum of 2 sessions (--max-sessions)"));
  EXPECT_EQ(registry.size(), 2);

  registry.Remove(&a);
  EXPECT_TRUE(registry.Add(&c).ok());
  EXPECT_EQ(registry.size(), 2);
  EXPECT_EQ(registry.Add(&a).error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
}

TEST(SessionRegistryTest, CloseIdleClosesExactlyTheSessionsIdleSinceBeforeTheCutoff) {
  const steady_clock::time_point cutoff = steady_clock::now();
  RecordingSession long_idle(cutoff - seconds(600));
  RecordingSession just_idle(cutoff - seconds(1));
  RecordingSession at_cutoff(cutoff);
  RecordingSession active(cutoff + seconds(5));
  SessionRegistry registry({.max_open = 8});
  for (RecordingSession* session : {&long_idle, &just_idle, &at_cutoff, &active}) {
    ASSERT_TRUE(registry.Add(session).ok());
  }

  registry.CloseIdle(cutoff, 30);

  for (const RecordingSession* idle : {&long_idle, &just_idle}) {
    ASSERT_EQ(idle->closed_with().size(), 1u);
    EXPECT_EQ(idle->closed_with()[0].error_code(), grpc::StatusCode::DEADLINE_EXCEEDED);
    EXPECT_THAT(idle->closed_with()[0].error_message(), HasSubstr("30 s without a frame"));
  }
  EXPECT_TRUE(at_cutoff.closed_with().empty());
  EXPECT_TRUE(active.closed_with().empty());
  // Closed sessions leave the registry themselves, when their stream is done.
  EXPECT_EQ(registry.size(), 4);
}

TEST(SessionRegistryTest, CloseAllClosesEverySessionWithTheGivenStatus) {
  SessionRegistry registry({.max_open = 8});
  RecordingSession a, b, c;
  for (RecordingSession* session : {&a, &b, &c}) ASSERT_TRUE(registry.Add(session).ok());
  registry.Remove(&b);

  registry.CloseAll({grpc::StatusCode::CANCELLED, "maintenance window"});

  for (const RecordingSession* open : {&a, &c}) {
    ASSERT_EQ(open->closed_with().size(), 1u);
    EXPECT_EQ(open->closed_with()[0].error_code(), grpc::StatusCode::CANCELLED);
    EXPECT_EQ(open->closed_with()[0].error_message(), "maintenance window");
  }
  EXPECT_TRUE(b.closed_with().empty());
}

TEST(SessionRegistryTest, RefusesNewSessionsAfterCloseAllEvenWhenEmpty) {
  SessionRegistry registry({.max_open = 8});
  RecordingSession open, late;
  ASSERT_TRUE(registry.Add(&open).ok());

  registry.CloseAll({grpc::StatusCode::UNAVAILABLE, "the server is shutting down"});
  EXPECT_EQ(registry.Add(&late).error_code(), grpc::StatusCode::UNAVAILABLE);
  EXPECT_EQ(registry.size(), 1);

  registry.Remove(&open);
  EXPECT_EQ(registry.Add(&late).error_code(), grpc::StatusCode::UNAVAILABLE);
  EXPECT_EQ(registry.size(), 0);
  EXPECT_TRUE(late.closed_with().empty());
}

TEST(SessionRegistryTest, RefusesATokenBeyondItsShareAndKeepsAdmittingOthers) {
  SessionRegistry registry({.max_open = 8, .max_open_per_token = 2});
  RecordingSession a, b, c, d, anonymous;
  ASSERT_TRUE(registry.Add(&a, "phone").ok());
  ASSERT_TRUE(registry.Add(&b, "phone").ok());
  const grpc::Status refused = registry.Add(&c, "phone");
  EXPECT_EQ(refused.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_THAT(refused.error_message(),
              HasSubstr("maximum of 2 sessions (--max-sessions-per-token)"));
  EXPECT_TRUE(registry.Add(&d, "drone").ok()) << "another token's share is its own";
  registry.Remove(&a);
  EXPECT_TRUE(registry.Add(&c, "phone").ok()) << "a slot freed by the token is its again";
  // Without access control there is no token to share by: only max_open applies.
  EXPECT_TRUE(registry.Add(&anonymous).ok());
  EXPECT_EQ(registry.size(), 4);
}

TEST(SessionRegistryTest, NamesItsKindInItsRefusals) {
  SessionRegistry registry(
      {.max_open = 1, .noun = "enrollment", .flag = "--max-enrollments", .activity = "a message"});
  RecordingSession a(steady_clock::now() - seconds(60)), b;
  ASSERT_TRUE(registry.Add(&a).ok());
  EXPECT_THAT(registry.Add(&b).error_message(),
              HasSubstr("maximum of 1 enrollments (--max-enrollments)"));
  registry.CloseIdle(steady_clock::now(), 30);
  ASSERT_EQ(a.closed_with().size(), 1u);
  EXPECT_EQ(a.closed_with()[0].error_message(), "enrollment closed after 30 s without a message");
}

}  // namespace
}  // namespace orbit::server
