#include "cli/process_usage.h"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace orbit {
namespace {

// Spins the CPU for `seconds` of wall time.
double Spin(double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  double x = 0;
  while (std::chrono::steady_clock::now() < end) x = std::sin(x + 1);
  return x;
}

TEST(ProcessUsageTest, ReadsThisProcessCpuTimeAndMemoryFromProc) {
  const ProcessUsage before = ReadProcessUsage(::getpid());
  const double own_before = OwnCpuSeconds();
  std::vector<char> touched(64 << 20, 1);  // 64 MiB, written: resident
  volatile double sink = Spin(0.3);
  (void)sink;
  const ProcessUsage after = ReadProcessUsage(::getpid());
  const double own_after = OwnCpuSeconds();

  // The spin ran on this process's CPU (at least a little of 0.3 s even on a busy machine),
  // seen both from /proc (10 ms ticks) and from getrusage.
  EXPECT_GT(after.cpu_seconds, before.cpu_seconds);
  EXPECT_GT(own_after - own_before, 0.01);
  // 64 MiB more are resident (a fresh mapping, not memory freed before).
  EXPECT_GE(after.rss_bytes - before.rss_bytes, std::int64_t{60} << 20);
  EXPECT_EQ(touched[12345], 1);
}

TEST(ProcessUsageTest, AProcessThatDoesNotExistIsAnError) {
  try {
    ReadProcessUsage(0x3fffffff);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no process 1073741823"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace orbit
