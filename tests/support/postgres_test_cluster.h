// PostgresTestCluster: a real PostgreSQL 15 server (Debian's postgresql-15) for the tests of the
// PostgreSQL model store, and TestDatabase, a fresh database on it per test.
//
// The server runs from a private folder: initdb'd there as an unprivileged user (initdb and
// postgres refuse root; as root the tests use `nobody`), listening only on a unix socket in that
// folder (no TCP port, nothing another test run can collide with), trust authentication for the
// superuser "orbit". fsync is off: the tests kill clients and processes, never the machine, and
// the server's own crash recovery does not depend on fsync when the kernel survives.
//
// One server per test run: ctest starts it once for every test named *Postgres* (the fixture
// orbit_postgres in tests/CMakeLists.txt, which passes its folder in $ORBIT_TEST_POSTGRES); a test
// binary run by hand starts its own on first use and stops it when the process exits. Tests
// stay apart by each using a database of its own.
//
// When the PostgreSQL binaries are missing, Shared() and Start() throw std::runtime_error naming
// the package: the test fails (never a skip). scripts/setup.sh installs them.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace orbit::testing {

// Where Debian installs PostgreSQL 15's server programs.
inline constexpr const char* kPostgresBinDir = "/usr/lib/postgresql/15/bin";

class PostgresTestCluster {
 public:
  // initdb's a new cluster in `folder` (a leftover one there is stopped and removed first) and
  // starts it. Returns once it accepts connections. Throws std::runtime_error with the server's
  // log when it cannot.
  static void Start(const std::filesystem::path& folder);
  // Stops the cluster in `folder` (if running) and removes the folder. Never throws.
  static void Stop(const std::filesystem::path& folder);
  // Stops the server in `folder` the way a crash would (pg_ctl stop --mode immediate: no
  // shutdown checkpoint; the next start replays the write-ahead log), keeping its data.
  static void Crash(const std::filesystem::path& folder);
  // Starts the server of the cluster in `folder` again, after Crash. Throws as Start.
  static void Restart(const std::filesystem::path& folder);

  // The cluster this process's tests use: the one in $ORBIT_TEST_POSTGRES, or one started in a
  // fresh temporary folder on the first call and stopped at exit.
  static PostgresTestCluster& Shared();

  ~PostgresTestCluster();
  PostgresTestCluster(const PostgresTestCluster&) = delete;
  PostgresTestCluster& operator=(const PostgresTestCluster&) = delete;

  // A libpq connection string for `database` on this cluster.
  std::string ConnectionString(const std::string& database) const;

  const std::filesystem::path& folder() const { return folder_; }

 private:
  PostgresTestCluster(std::filesystem::path folder, bool owned);

  std::filesystem::path folder_;
  int owner_pid_ = 0;  // the process that started it and stops it; 0: started by someone else
};

// A PostgreSQL server of the test's own, for tests that crash or restart it while the shared one
// serves other tests: started in a fresh temporary folder, stopped and removed at the end.
class PrivatePostgresServer {
 public:
  PrivatePostgresServer();  // throws as PostgresTestCluster::Start
  ~PrivatePostgresServer();
  PrivatePostgresServer(const PrivatePostgresServer&) = delete;
  PrivatePostgresServer& operator=(const PrivatePostgresServer&) = delete;

  // The connection string of its database "postgres".
  std::string conninfo() const;
  const std::filesystem::path& folder() const { return folder_; }
  void Crash() const { PostgresTestCluster::Crash(folder_); }
  void Restart() const { PostgresTestCluster::Restart(folder_); }

 private:
  std::filesystem::path parent_;  // the temporary folder, holding folder_
  std::filesystem::path folder_;
};

// A new empty database on the shared cluster, dropped (with any connection left to it) at the
// end of the test.
class TestDatabase {
 public:
  TestDatabase();
  ~TestDatabase();
  TestDatabase(const TestDatabase&) = delete;
  TestDatabase& operator=(const TestDatabase&) = delete;

  const std::string& name() const { return name_; }
  // The connection string of this database, as `orbit serve --store` takes it.
  const std::string& conninfo() const { return conninfo_; }

  // Runs `sql` on the database on a connection of its own, bypassing the store (to look at the
  // tables or inject failures). Throws StoreError as the store would.
  void Execute(const std::string& sql) const;
  // The single value `sql` returns, as text / as a number.
  std::string Text(const std::string& sql) const;
  std::int64_t Int(const std::string& sql) const { return std::stoll(Text(sql)); }

 private:
  std::string name_;
  std::string conninfo_;
};

}  // namespace orbit::testing
