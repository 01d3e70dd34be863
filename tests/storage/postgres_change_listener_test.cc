// PostgresChangeListener on a real PostgreSQL server: a commit wakes the wait at once, a quiet
// database lets it time out, and a connection the server ends is an error, never a silent hang.
#include "storage/postgres_change_listener.h"

#include <chrono>
#include <thread>

#include <gtest/gtest.h>

#include "storage/postgres_model_store.h"
#include "storage/store_error.h"
#include "tests/support/postgres_test_cluster.h"
#include "tests/support/storage_test_support.h"

namespace orbit {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;
using testing::SyntheticObject;
using testing::TestDatabase;

TEST(PostgresChangeListenerTest, ACommitWakesTheWaitAndAQuietStoreTimesOut) {
  TestDatabase database;
  PostgresModelStore store(database.conninfo());
  PostgresChangeListener listener(database.conninfo());

  Clock::time_point start = Clock::now();
  EXPECT_FALSE(listener.Wait(milliseconds(300)));
  EXPECT_GE(Clock::now() - start, milliseconds(250));

  std::thread writer([&] {
    std::this_thread::sleep_for(milliseconds(200));
    store.Enroll(SyntheticObject("mug", 2));
  });
  start = Clock::now();
  const bool woken = listener.Wait(milliseconds(20000));
  const Clock::duration waited = Clock::now() - start;
  writer.join();
  EXPECT_TRUE(woken);
  EXPECT_LT(waited, milliseconds(10000));  // woken by the commit, long before the timeout

  // Two commits while nobody waits: one wait consumes both, the next times out.
  store.Enroll(SyntheticObject("jar", 2));
  store.Enroll(SyntheticObject("pot", 2));
  std::this_thread::sleep_for(milliseconds(200));
  EXPECT_TRUE(listener.Wait(milliseconds(5000)));
  EXPECT_FALSE(listener.Wait(milliseconds(200)));
}

TEST(PostgresChangeListenerTest, AConnectionTheServerEndsIsAnError) {
  TestDatabase database;
  PostgresChangeListener listener(database.conninfo());
  ASSERT_GE(database.Int("SELECT count(pg_terminate_backend(pid, 5000)) FROM pg_stat_activity "
                         "WHERE datname = current_database() AND pid <> pg_backend_pid()"),
            1);
  try {
    for (int i = 0; i < 50; ++i) listener.Wait(milliseconds(100));
    FAIL() << "the wait went on after the server ended the connection";
  } catch (const StoreError& e) {
    EXPECT_EQ(e.code(), StoreError::Code::kIo);
    EXPECT_NE(std::string(e.what()).find("lost the connection to PostgreSQL"), std::string::npos)
        << e.what();
  }
}

TEST(PostgresChangeListenerTest, AnUnreachableServerIsAnErrorAtOnce) {
  testing::ScratchDir dir;  // no server's socket in it
  EXPECT_THROW(PostgresChangeListener("host=" + dir.path().string() + " dbname=models"),
               StoreError);
}

}  // namespace
}  // namespace orbit
