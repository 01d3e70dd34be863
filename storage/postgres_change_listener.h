// PostgresChangeListener: wakes a follower of the PostgreSQL store's change log when another
// writer commits (LISTEN orbit_model_changes; storage/postgres_model_store.h, "Change log").
//
// A notification only says "something was committed": the follower then reads the log with
// PostgresModelStore::ChangesAfter from the last seq it applied, so a notification lost with a
// dropped connection loses nothing (after reconnecting, the follower reads the log again).
//
//   PostgresChangeListener listener(conninfo);         // LISTENs from now on
//   for (;;) {
//     apply store.ChangesAfter(last_seq) ...
//     listener.Wait(std::chrono::seconds(1));           // a commit, or the timeout
//   }
//
// Not thread-safe: one thread waits on a listener.
#pragma once

#include <chrono>
#include <memory>
#include <string>

namespace orbit {

class PostgresConnection;

class PostgresChangeListener {
 public:
  // Connects to `conninfo` on a connection of its own and LISTENs. Throws StoreError kIo as
  // PostgresConnection when the server cannot be reached.
  explicit PostgresChangeListener(const std::string& conninfo);
  ~PostgresChangeListener();

  PostgresChangeListener(const PostgresChangeListener&) = delete;
  PostgresChangeListener& operator=(const PostgresChangeListener&) = delete;

  // Waits up to `timeout` for a change to be committed; true when one was (or several: they are
  // all consumed), false at the timeout. Throws StoreError kIo when the connection is lost (the
  // server restarted or ended it); the listener is then useless: make a new one.
  bool Wait(std::chrono::milliseconds timeout);

 private:
  std::unique_ptr<PostgresConnection> connection_;
};

}  // namespace orbit
