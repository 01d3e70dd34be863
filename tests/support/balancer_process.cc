#include "tests/support/balancer_process.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <grpcpp/grpcpp.h>

#include "orbit/v1/models.grpc.pb.h"
#include "tests/support/free_port.h"

namespace orbit::testing {

using Clock = std::chrono::steady_clock;

BalancerProcess::BalancerProcess(const std::vector<std::string>& replicas) {
  if (replicas.empty() || replicas.size() > 3) {
    throw std::invalid_argument("docker/haproxy.cfg has room for 1 to 3 replicas");
  }
  std::string pattern = (std::filesystem::temp_directory_path() / "orbit_balancer_XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
  temp_dir_ = pattern;
  log_file_ = temp_dir_ / "haproxy.log";
  address_ = "127.0.0.1:" + std::to_string(FreeLoopbackPort());

  std::vector<std::string> environment = {"ORBIT_BALANCER_LISTEN=" + address_};
  for (std::size_t slot = 0; slot < 3; ++slot) {
    // A port nothing listens on: HAProxy marks the slot down at its first check.
    const std::string target = slot < replicas.size() ? replicas[slot] : "127.0.0.1:1";
    environment.push_back("ORBIT_REPLICA_" + std::to_string(slot + 1) + "=" + target);
  }
  const std::string config = std::string(ORBIT_SOURCE_DIR) + "/docker/haproxy.cfg";
  pid_ = ::fork();
  if (pid_ < 0) throw std::runtime_error("fork failed");
  if (pid_ == 0) {
    const int fd = ::open(log_file_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, STDOUT_FILENO);
    ::dup2(fd, STDERR_FILENO);
    for (const std::string& variable : environment) ::putenv(const_cast<char*>(variable.c_str()));
    ::execlp("haproxy", "haproxy", "-f", config.c_str(), "-db", static_cast<char*>(nullptr));
    _exit(127);
  }

  // Serving: a call through the balancer reaches a replica.
  const auto channel = grpc::CreateChannel(address_, grpc::InsecureChannelCredentials());
  const auto stub = v1::Models::NewStub(channel);
  const Clock::time_point deadline = Clock::now() + std::chrono::seconds(30);
  for (;;) {
    int status = 0;
    if (::waitpid(pid_, &status, WNOHANG) == pid_) {
      pid_ = -1;
      throw std::runtime_error("haproxy exited at start (is the haproxy package installed?):\n" +
                               Log());
    }
    grpc::ClientContext context;
    context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(2));
    v1::ServerInfoResponse info;
    if (stub->ServerInfo(&context, v1::ServerInfoRequest(), &info).ok()) break;
    if (Clock::now() > deadline) {
      throw std::runtime_error("haproxy did not start serving within 30 s:\n" + Log());
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  for (std::size_t slot = replicas.size(); slot < 3; ++slot) {
    if (!WaitUntilDown(static_cast<int>(slot) + 1, std::chrono::seconds(10))) {
      throw std::runtime_error("haproxy did not mark the unused replica slot down:\n" + Log());
    }
  }
}

BalancerProcess::~BalancerProcess() {
  if (pid_ > 0) {
    ::kill(pid_, SIGTERM);
    int status = 0;
    ::waitpid(pid_, &status, 0);
  }
  std::error_code ignored;
  std::filesystem::remove_all(temp_dir_, ignored);
}

std::string BalancerProcess::Log() const {
  std::ifstream in(log_file_);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

bool BalancerProcess::WaitForLine(const std::string& text,
                                  std::chrono::milliseconds timeout) const {
  const Clock::time_point deadline = Clock::now() + timeout;
  while (Log().find(text) == std::string::npos) {
    if (Clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return true;
}

bool BalancerProcess::WaitUntilDown(int slot, std::chrono::milliseconds timeout) const {
  return WaitForLine("replicas/replica-" + std::to_string(slot) + " is DOWN", timeout);
}

bool BalancerProcess::WaitUntilUp(int slot, std::chrono::milliseconds timeout) const {
  return WaitForLine("replicas/replica-" + std::to_string(slot) + " is UP", timeout);
}

}  // namespace orbit::testing
