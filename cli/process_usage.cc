#include "cli/process_usage.h"

#include <sys/resource.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace orbit {

ProcessUsage ReadProcessUsage(pid_t pid) {
  const std::string path = "/proc/" + std::to_string(pid) + "/stat";
  std::ifstream in(path);
  std::string line;
  if (!in || !std::getline(in, line)) {
    throw std::runtime_error("cannot read " + path + ": no process " + std::to_string(pid) +
                             " on this machine");
  }
  // "pid (comm) state ppid ...": comm may hold spaces and parentheses, so the fields are
  // counted from the last ')'. proc(5): utime is field 14, stime 15, rss (pages) 24; the
  // state after ')' is field 3.
  const std::size_t close = line.rfind(')');
  if (close == std::string::npos) throw std::runtime_error("cannot parse " + path);
  std::istringstream fields(line.substr(close + 1));
  std::string field;
  long long utime = -1, stime = -1, rss = -1;
  for (int number = 3; fields >> field && number <= 24; ++number) {
    if (number == 14) utime = std::stoll(field);
    if (number == 15) stime = std::stoll(field);
    if (number == 24) rss = std::stoll(field);
  }
  if (utime < 0 || stime < 0 || rss < 0) throw std::runtime_error("cannot parse " + path);
  ProcessUsage usage;
  usage.cpu_seconds =
      static_cast<double>(utime + stime) / static_cast<double>(::sysconf(_SC_CLK_TCK));
  usage.rss_bytes = rss * static_cast<std::int64_t>(::sysconf(_SC_PAGESIZE));
  return usage;
}

double OwnCpuSeconds() {
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  const auto seconds = [](const timeval& t) { return t.tv_sec + t.tv_usec / 1e6; };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

}  // namespace orbit
