// What a process has cost so far, for `orbit loadtest`: the server's CPU time and resident memory
// read from /proc (Linux, same machine only), and the generator's own CPU time.
#pragma once

#include <sys/types.h>

#include <cstdint>

namespace orbit {

struct ProcessUsage {
  double cpu_seconds = 0;      // user + system time of every thread since the process started
  std::int64_t rss_bytes = 0;  // resident set size now
};

// Reads /proc/PID/stat (utime, stime and rss; CPU time counts in clock ticks, 10 ms on most
// kernels, so a difference is meaningful over seconds, not milliseconds). Throws
// std::runtime_error naming the process when it does not exist or the file cannot be parsed.
ProcessUsage ReadProcessUsage(pid_t pid);

// This process's user + system CPU time so far (getrusage), in seconds, to microseconds.
double OwnCpuSeconds();

}  // namespace orbit
