// Child: a forked child process whose output a test reads line by line and which it kills with
// SIGKILL mid-work (the crash tests of the stores: tests/storage/*_crash_test.cc).
#pragma once

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace orbit::testing {

// A child process whose stdout the test reads line by line, to be killed with SIGKILL.
class Child {
 public:
  // Runs `body` in a forked child with stdout on a pipe; `body` returns the exit status.
  template <typename Body>
  explicit Child(Body body) {
    int fds[2];
    if (::pipe(fds) != 0) throw std::runtime_error("pipe failed");
    std::fflush(nullptr);
    pid_ = ::fork();
    if (pid_ < 0) throw std::runtime_error("fork failed");
    if (pid_ == 0) {
      ::close(fds[0]);
      ::dup2(fds[1], STDOUT_FILENO);
      ::close(fds[1]);
      ::_exit(body());
    }
    ::close(fds[1]);
    out_ = ::fdopen(fds[0], "r");
  }
  ~Child() {
    if (pid_ > 0 && !reaped_) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    if (out_ != nullptr) std::fclose(out_);
  }

  // The next line the child printed, without "\n"; "" at end of output.
  std::string ReadLine() {
    std::string line;
    for (int c = std::fgetc(out_); c != EOF && c != '\n'; c = std::fgetc(out_)) line += char(c);
    return line;
  }

  // SIGKILL, then the lines printed before it. Returns false when the child had already exited
  // (the kill came too late to be a crash).
  bool Kill(std::vector<std::string>& rest) {
    const bool running = ::kill(pid_, SIGKILL) == 0;
    int status = 0;
    ::waitpid(pid_, &status, 0);
    reaped_ = true;
    for (std::string line = ReadLine(); !line.empty(); line = ReadLine()) rest.push_back(line);
    return running && WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
  }

 private:
  pid_t pid_ = -1;
  bool reaped_ = false;
  FILE* out_ = nullptr;
};

// The names in lines "enrolled NAME ...".
inline std::set<std::string> Acknowledged(const std::vector<std::string>& lines) {
  std::set<std::string> names;
  for (const std::string& line : lines) {
    if (line.rfind("enrolled ", 0) == 0) names.insert(line.substr(9, line.find(' ', 9) - 9));
  }
  return names;
}

}  // namespace orbit::testing
