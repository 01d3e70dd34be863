#include "tests/support/postgres_test_cluster.h"

#include <fcntl.h>
#include <grp.h>
#include <pwd.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "storage/postgres_connection.h"

namespace orbit::testing {
namespace {

// The user the server runs as: the current one, or `nobody` for root.
struct ServerUser {
  uid_t uid;
  gid_t gid;
};

ServerUser UnprivilegedUser() {
  if (::geteuid() != 0) return {::geteuid(), ::getegid()};
  const passwd* nobody = ::getpwnam("nobody");
  if (nobody == nullptr) {
    throw std::runtime_error("tests run as root and there is no user `nobody` to run PostgreSQL");
  }
  return {nobody->pw_uid, nobody->pw_gid};
}

std::string Program(const char* name) {
  const std::filesystem::path program = std::filesystem::path(kPostgresBinDir) / name;
  if (::access(program.c_str(), X_OK) != 0) {
    throw std::runtime_error(program.string() +
                             " is missing: the PostgreSQL tests need Debian's postgresql-15 "
                             "(run scripts/setup.sh)");
  }
  return program.string();
}

// Runs `arguments` (the program first) as the server's user in `folder`, its output appended to
// folder/commands.log; returns the exit status (-1 when it did not exit normally).
int RunAsServerUser(const std::filesystem::path& folder,
                    const std::vector<std::string>& arguments) {
  const ServerUser user = UnprivilegedUser();
  std::vector<char*> argv;
  for (const std::string& argument : arguments) argv.push_back(const_cast<char*>(argument.c_str()));
  argv.push_back(nullptr);
  const std::string log = (folder / "commands.log").string();
  const int log_fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    // Only async-signal-safe calls between fork and exec.
    if (log_fd >= 0) {
      ::dup2(log_fd, STDOUT_FILENO);
      ::dup2(log_fd, STDERR_FILENO);
    }
    if (::geteuid() == 0 &&
        (::setgroups(0, nullptr) != 0 || ::setgid(user.gid) != 0 || ::setuid(user.uid) != 0)) {
      ::_exit(126);
    }
    if (::chdir(folder.c_str()) != 0) ::_exit(126);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  if (log_fd >= 0) ::close(log_fd);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string FileText(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string PgCtl() { return Program("pg_ctl"); }

}  // namespace

void PostgresTestCluster::Start(const std::filesystem::path& folder) {
  const std::string initdb = Program("initdb");
  PgCtl();
  Program("postgres");
  Stop(folder);
  std::filesystem::create_directories(folder);
  const ServerUser user = UnprivilegedUser();
  if (::chown(folder.c_str(), user.uid, user.gid) != 0 || ::chmod(folder.c_str(), 0700) != 0) {
    throw std::runtime_error("cannot hand " + folder.string() + " to the server's user");
  }
  const std::string data = (folder / "data").string();
  if (RunAsServerUser(
          folder, {initdb, "--pgdata", data, "--username", "orbit", "--auth", "trust", "--encoding",
                   "UTF8", "--locale", "C", "--no-sync", "--no-instructions"}) != 0) {
    throw std::runtime_error("initdb failed in " + folder.string() + ":\n" +
                             FileText(folder / "commands.log"));
  }
  Restart(folder);
}

void PostgresTestCluster::Restart(const std::filesystem::path& folder) {
  const std::string settings = "-c listen_addresses='' -c unix_socket_directories='" +
                               folder.string() +
                               "' -c fsync=off -c shared_buffers=16MB -c max_connections=200";
  if (RunAsServerUser(folder, {PgCtl(), "start", "--pgdata", (folder / "data").string(), "--wait",
                               "--timeout", "60", "--silent", "--log",
                               (folder / "server.log").string(), "-o", settings}) != 0) {
    throw std::runtime_error("PostgreSQL did not start in " + folder.string() + ":\n" +
                             FileText(folder / "commands.log") + FileText(folder / "server.log"));
  }
}

void PostgresTestCluster::Crash(const std::filesystem::path& folder) {
  if (RunAsServerUser(folder, {PgCtl(), "stop", "--pgdata", (folder / "data").string(), "--wait",
                               "--silent", "--mode", "immediate"}) != 0) {
    throw std::runtime_error("pg_ctl stop --mode immediate failed in " + folder.string() + ":\n" +
                             FileText(folder / "commands.log"));
  }
}

void PostgresTestCluster::Stop(const std::filesystem::path& folder) {
  std::error_code ignored;
  if (std::filesystem::exists(folder / "data" / "postmaster.pid", ignored)) {
    try {
      RunAsServerUser(folder, {PgCtl(), "stop", "--pgdata", (folder / "data").string(), "--wait",
                               "--silent", "--mode", "fast"});
    } catch (...) {
      // Nothing more to try: the folder goes anyway.
    }
  }
  std::filesystem::remove_all(folder, ignored);
}

PostgresTestCluster& PostgresTestCluster::Shared() {
  static PostgresTestCluster cluster = [] {
    if (const char* folder = std::getenv("ORBIT_TEST_POSTGRES"); folder != nullptr && *folder) {
      return PostgresTestCluster(folder, /*owned=*/false);
    }
    const std::filesystem::path folder = std::filesystem::temp_directory_path() /
                                         ("orbit_test_postgres_" + std::to_string(::getpid()));
    try {
      Start(folder);
    } catch (...) {
      Stop(folder);  // a server that started too slowly, a half-made folder
      throw;
    }
    return PostgresTestCluster(folder, /*owned=*/true);
  }();
  return cluster;
}

PostgresTestCluster::PostgresTestCluster(std::filesystem::path folder, bool owned)
    : folder_(std::move(folder)), owner_pid_(owned ? ::getpid() : 0) {}

PostgresTestCluster::~PostgresTestCluster() {
  // Not in a forked child that exits normally: the cluster is its parent's.
  if (owner_pid_ != 0 && owner_pid_ == ::getpid()) Stop(folder_);
}

PrivatePostgresServer::PrivatePostgresServer() {
  std::string pattern =
      (std::filesystem::temp_directory_path() / "orbit_private_postgres_XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
  parent_ = pattern;
  ::chmod(parent_.c_str(), 0755);  // the server's unprivileged user must reach its folder
  folder_ = parent_ / "cluster";
  try {
    PostgresTestCluster::Start(folder_);
  } catch (...) {
    PostgresTestCluster::Stop(folder_);
    std::error_code ignored;
    std::filesystem::remove_all(parent_, ignored);
    throw;
  }
}

PrivatePostgresServer::~PrivatePostgresServer() {
  PostgresTestCluster::Stop(folder_);
  std::error_code ignored;
  std::filesystem::remove_all(parent_, ignored);
}

std::string PrivatePostgresServer::conninfo() const {
  return "host=" + folder_.string() + " user=orbit dbname=postgres";
}

std::string PostgresTestCluster::ConnectionString(const std::string& database) const {
  return "host=" + folder_.string() + " user=orbit dbname=" + database;
}

TestDatabase::TestDatabase() {
  static std::atomic<int> counter{0};
  name_ = "orbit_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
  const PostgresTestCluster& cluster = PostgresTestCluster::Shared();
  conninfo_ = cluster.ConnectionString(name_);
  PostgresConnection admin(cluster.ConnectionString("postgres"), 0);
  admin.Execute("DROP DATABASE IF EXISTS " + name_ + " WITH (FORCE)");
  admin.Execute("CREATE DATABASE " + name_);
}

TestDatabase::~TestDatabase() {
  try {
    PostgresConnection admin(PostgresTestCluster::Shared().ConnectionString("postgres"), 0);
    admin.Execute("DROP DATABASE IF EXISTS " + name_ + " WITH (FORCE)");
  } catch (...) {
    // Left behind: it goes with the cluster.
  }
}

void TestDatabase::Execute(const std::string& sql) const {
  PostgresConnection(conninfo_, 0).Execute(sql);
}

std::string TestDatabase::Text(const std::string& sql) const {
  const PostgresResult result = PostgresConnection(conninfo_, 0).Query(sql);
  if (result.rows() != 1) throw std::runtime_error("`" + sql + "` gave no single row");
  return result.IsNull(0, 0) ? "NULL" : result.Text(0, 0);
}

}  // namespace orbit::testing
