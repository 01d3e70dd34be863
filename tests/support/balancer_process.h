// BalancerProcess: Debian's HAProxy running docker/haproxy.cfg on loopback in front of server
// replicas, for the tests of a replicated deployment (tests/docker/replicas_test.cc). The same
// file the compose deployment uses, with the addresses given through its environment variables.
//
//   BalancerProcess balancer({a.address(), b.address()});   // waits until it serves
//   Connection connection(At(balancer.address()));
//
// The destructor stops HAProxy. Throws std::runtime_error with HAProxy's log when it does not
// start (the haproxy package missing: scripts/setup.sh installs it).
#pragma once

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

namespace orbit::testing {

class BalancerProcess {
 public:
  // Up to three replicas (HOST:PORT), as replica-1, replica-2, replica-3; the slots left over
  // point at a closed port. Returns once a call through the balancer succeeds and the unused
  // slots are marked down, so every stream then goes to a given replica.
  explicit BalancerProcess(const std::vector<std::string>& replicas);
  ~BalancerProcess();

  BalancerProcess(const BalancerProcess&) = delete;
  BalancerProcess& operator=(const BalancerProcess&) = delete;

  // "127.0.0.1:PORT" where clients connect.
  const std::string& address() const { return address_; }

  // Waits up to `timeout` until HAProxy has marked replica-`slot` (1..3) down; false if not.
  bool WaitUntilDown(int slot, std::chrono::milliseconds timeout) const;
  // Waits up to `timeout` until HAProxy has marked replica-`slot` up again after it was down.
  bool WaitUntilUp(int slot, std::chrono::milliseconds timeout) const;

  // Everything HAProxy logged so far.
  std::string Log() const;

 private:
  bool WaitForLine(const std::string& text, std::chrono::milliseconds timeout) const;

  std::filesystem::path temp_dir_;
  std::filesystem::path log_file_;
  std::string address_;
  pid_t pid_ = -1;
};

}  // namespace orbit::testing
