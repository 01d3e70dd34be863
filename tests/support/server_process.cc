#include "tests/support/server_process.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "tests/support/test_data.h"

namespace orbit::testing {
namespace {

std::filesystem::path MakeTempDir() {
  std::string pattern = (std::filesystem::temp_directory_path() / "orbit_server_XXXXXX").string();
  if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
  return pattern;
}

// fork + exec `binary` with `args`, stdout and stderr into `log`, under `descriptor_limit`.
pid_t Spawn(const std::string& binary, const std::vector<std::string>& args,
            const std::filesystem::path& log, std::optional<int> descriptor_limit) {
  std::vector<std::string> argv_storage = {binary};
  argv_storage.insert(argv_storage.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : argv_storage) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, STDOUT_FILENO);
    dup2(fd, STDERR_FILENO);
    if (descriptor_limit) {
      const rlimit limit{static_cast<rlim_t>(*descriptor_limit),
                         static_cast<rlim_t>(*descriptor_limit)};
      if (setrlimit(RLIMIT_NOFILE, &limit) != 0) _exit(126);
    }
    execv(argv[0], argv.data());
    _exit(127);
  }
  return pid;
}

std::string Slurp(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Waits for the child to exit; returns its code (128 + signal), or -1 at the timeout.
int WaitExit(pid_t pid, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    int status = 0;
    const pid_t done = waitpid(pid, &status, WNOHANG);
    if (done == pid) {
      return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }
    if (std::chrono::steady_clock::now() > deadline) return -1;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

}  // namespace

ServerProcess::ServerProcess(ServerProcessOptions options) {
  temp_dir_ = MakeTempDir();
  log_file_ = temp_dir_ / "server.log";
  owns_database_ = !options.database.has_value();
  database_ = options.database.value_or(temp_dir_ / "models.db");
  std::vector<std::string> args = {"serve", "--listen", options.listen, "--workers",
                                   std::to_string(options.workers)};
  if (options.store) {
    args.insert(args.end(), {"--store", *options.store});
  } else {
    args.insert(args.end(), {"--db", database_.string()});
  }
  if (options.tokens_file) args.insert(args.end(), {"--tokens", options.tokens_file->string()});
  if (options.tls_cert) args.insert(args.end(), {"--tls-cert", options.tls_cert->string()});
  if (options.tls_key) args.insert(args.end(), {"--tls-key", options.tls_key->string()});
  if (options.metrics) args.insert(args.end(), {"--metrics-listen", "127.0.0.1:0"});
  args.insert(args.end(), options.extra_args.begin(), options.extra_args.end());
  pid_ = Spawn(options.binary, args, log_file_, options.descriptor_limit);

  const std::string marker = "listening on ";
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  for (;;) {
    const std::string log = Slurp(log_file_);
    if (options.wait_until == ServerProcessOptions::Until::kLoading &&
        log.find("orbit serve: loading the store") != std::string::npos) {
      address_ = options.listen;
      return;
    }
    if (const auto at = log.find(marker);
        at != std::string::npos && log.find('\n', at) != std::string::npos) {
      address_ = log.substr(at + marker.size(), log.find('\n', at) - at - marker.size());
      port_ = std::stoi(address_.substr(address_.rfind(':') + 1));
      // Printed before "listening on", as "metrics on http://HOST:PORT/metrics".
      const std::string metrics_marker = "metrics on http://";
      if (const auto m = log.find(metrics_marker); m != std::string::npos) {
        const auto begin = m + metrics_marker.size();
        metrics_address_ = log.substr(begin, log.find("/metrics", begin) - begin);
      }
      return;
    }
    const int code = WaitExit(pid_, std::chrono::milliseconds(0));
    if (code >= 0 || std::chrono::steady_clock::now() > deadline) {
      if (code < 0) Stop(SIGKILL);
      pid_ = -1;
      throw std::runtime_error("orbit serve did not start (exit " + std::to_string(code) + "):\n" +
                               log);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

ServerProcess::~ServerProcess() {
  if (pid_ > 0) {
    // A server stops cleanly on SIGTERM. One that crashed during the test, hangs in its
    // shutdown, or reports a finding at exit (under scripts/sanitize.sh; UBSan writes to stderr
    // only) fails the test, showing the log that is removed below.
    const int code = Stop(SIGTERM, std::chrono::seconds(10));
    if (code < 0) Stop(SIGKILL);
    if (code != 0) {
      ADD_FAILURE() << "orbit serve did not stop cleanly on SIGTERM ("
                    << (code < 0 ? "still running after 10 s" : "exit " + std::to_string(code))
                    << "); its log:\n"
                    << Log();
    }
  }
  std::error_code ignored;
  if (owns_database_)
    std::filesystem::remove_all(temp_dir_, ignored);
  else
    std::filesystem::remove(log_file_, ignored);
}

int ServerProcess::Stop(int signal, std::chrono::seconds timeout) {
  if (pid_ <= 0) return -1;
  kill(pid_, signal);
  const int code = WaitExit(pid_, timeout);
  if (code >= 0) pid_ = -1;
  return code;
}

std::string ServerProcess::Log() const { return Slurp(log_file_); }

RefusedStart StartServerExpectingRefusal(const std::vector<std::string>& args) {
  const std::filesystem::path dir = MakeTempDir();
  const pid_t pid = Spawn(OrbitBinary(), args, dir / "server.log", std::nullopt);
  RefusedStart result;
  result.exit_code = WaitExit(pid, std::chrono::seconds(30));
  if (result.exit_code < 0) {
    kill(pid, SIGKILL);
    WaitExit(pid, std::chrono::seconds(5));
  }
  result.log = Slurp(dir / "server.log");
  std::error_code ignored;
  std::filesystem::remove_all(dir, ignored);
  return result;
}

void WriteTokenFile(const std::filesystem::path& file, const std::string& lines) {
  std::ofstream(file) << lines;
  std::filesystem::permissions(
      file, std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
}

void MakeSelfSignedCertificate(const std::filesystem::path& dir, const std::string& common_name,
                               const std::string& subject_alt_names) {
  const std::string command =
      "openssl req -x509 -newkey rsa:2048 -nodes -days 2 -subj /CN=" + common_name +
      " -addext subjectAltName=" + subject_alt_names + " -keyout " + (dir / "key.pem").string() +
      " -out " + (dir / "cert.pem").string() + " 2>/dev/null";
  if (std::system(command.c_str()) != 0) {
    throw std::runtime_error("openssl could not make a test certificate in " + dir.string());
  }
}

ServerProcessOptions SecuredServerOptions(const std::filesystem::path& dir, const std::string& host,
                                          const std::string& admin_token,
                                          const std::string& reader_token) {
  std::filesystem::create_directories(dir);
  WriteTokenFile(dir / "tokens",
                 "# operators\n" + admin_token + " admin\n" + reader_token + " recognize\n");
  std::ofstream(dir / "reader.token") << "# the device's token\n" << reader_token << "\n";
  MakeSelfSignedCertificate(dir, host, "DNS:" + host);
  ServerProcessOptions options;
  options.tokens_file = dir / "tokens";
  options.tls_cert = dir / "cert.pem";
  options.tls_key = dir / "key.pem";
  return options;
}

}  // namespace orbit::testing
