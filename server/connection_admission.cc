#include "server/connection_admission.h"

#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>

#include "core/base/mutex.h"

namespace orbit::server {
namespace {

using AcceptFunction = int (*)(int, sockaddr*, socklen_t*, int);

std::atomic<int> reserve{0};  // 0: not admitting (accept4 is the C library's alone)
std::atomic<std::int64_t> refused{0};

// The spare descriptor that lets a full table still take a waiting connection off the listen
// queue to close it; -1 while lent out or not yet opened.
Mutex spare_mutex;
int spare ABSL_GUARDED_BY(spare_mutex) = -1;

// The soft limit on descriptors, as the kernel applies it to the next one allocated.
rlim_t DescriptorLimit() {
  rlimit limit{};
  getrlimit(RLIMIT_NOFILE, &limit);
  return limit.rlim_cur;
}

// Says on stderr that connections are being refused, at most every 10 s: an operator sees why
// clients cannot connect, and a flood cannot fill the log.
void ReportRefusal(int keep) {
  static std::atomic<std::int64_t> last_report{0};
  const std::int64_t now = std::chrono::duration_cast<std::chrono::seconds>(
                               std::chrono::steady_clock::now().time_since_epoch())
                               .count();
  std::int64_t last = last_report.load(std::memory_order_relaxed);
  if (last != 0 && now - last < 10) return;
  if (!last_report.compare_exchange_strong(last, now)) return;
  // fprintf, not a stream: no allocation, no locale, from whichever thread gRPC accepts on.
  std::fprintf(stderr,
               "orbit: refusing new connections: fewer than %d descriptors would stay free under "
               "the limit of %llu (ulimit -n); %lld refused so far\n",
               keep, static_cast<unsigned long long>(DescriptorLimit()),
               static_cast<long long>(refused.load(std::memory_order_relaxed)));
}

// The next accept4 in the lookup order: the C library's, or a sanitizer's interceptor of it.
AcceptFunction NextAccept4() {
  static const auto next = reinterpret_cast<AcceptFunction>(dlsym(RTLD_NEXT, "accept4"));
  return next;
}

// False when descriptor `fd` leaves fewer than `keep` free: the kernel hands out the lowest free
// number, so every descriptor below `fd` is open. Descriptors above `fd` may be open too (left by
// ones closed below them), so true does not promise `keep` free; a table that fills anyway ends
// at EMFILE, which accept4 below answers without harm. Costs one getrlimit, no scan of the table.
bool LeavesFree(int fd, int keep) {
  const rlim_t limit = DescriptorLimit();
  return limit == RLIM_INFINITY || static_cast<rlim_t>(fd) + 1 + keep <= limit;
}

// With the table full: lends the spare descriptor's slot to accept one waiting connection and
// close it, for every connection waiting. Returns false when none could be taken (the spare was
// lent to another thread, or another descriptor took its slot).
bool TakeAndCloseWaiting(AcceptFunction accept, int listener) {
  // A blocking listener would wait here for a connection that may never come: take one at most.
  const bool one_only = (fcntl(listener, F_GETFL) & O_NONBLOCK) == 0;
  MutexLock lock(&spare_mutex);
  if (spare < 0) return false;
  close(spare);
  spare = -1;
  bool took = false;
  for (;;) {
    const int connection = accept(listener, nullptr, nullptr, SOCK_CLOEXEC);
    if (connection < 0) break;
    close(connection);
    refused.fetch_add(1, std::memory_order_relaxed);
    took = true;
    ReportRefusal(reserve.load(std::memory_order_relaxed));
    if (one_only) break;
  }
  spare = open("/dev/null", O_RDONLY | O_CLOEXEC);
  return took;
}

}  // namespace

void AdmitConnectionsKeepingFree(int keep) {
  rlimit limit{};
  if (getrlimit(RLIMIT_NOFILE, &limit) == 0 && limit.rlim_cur < limit.rlim_max) {
    limit.rlim_cur = limit.rlim_max;
    setrlimit(RLIMIT_NOFILE, &limit);
  }
  {
    MutexLock lock(&spare_mutex);
    if (spare < 0) spare = open("/dev/null", O_RDONLY | O_CLOEXEC);
  }
  reserve.store(keep < 8 ? 8 : keep, std::memory_order_relaxed);
}

std::int64_t RefusedConnections() { return refused.load(std::memory_order_relaxed); }

}  // namespace orbit::server

// The process's accept4 (see connection_admission.h). Declared by <sys/socket.h>; an executable's
// definition comes first in the dynamic linker's lookup, so gRPC's calls arrive here.
extern "C" int accept4(int listener, sockaddr* address, socklen_t* address_length, int flags) {
  using orbit::server::AcceptFunction;
  const AcceptFunction next = orbit::server::NextAccept4();
  const int keep = orbit::server::reserve.load(std::memory_order_relaxed);
  for (;;) {
    const int connection = next(listener, address, address_length, flags);
    if (keep == 0) return connection;
    if (connection >= 0) {
      if (orbit::server::LeavesFree(connection, keep)) return connection;
      close(connection);  // the reserve is for the store, the logs and calls already admitted
      orbit::server::refused.fetch_add(1, std::memory_order_relaxed);
      orbit::server::ReportRefusal(keep);
      continue;  // refuse every connection waiting, then report none left (EAGAIN)
    }
    if (errno != EMFILE && errno != ENFILE) return connection;
    if (!orbit::server::TakeAndCloseWaiting(next, listener)) {
      // Nothing taken: report an empty queue rather than the full table, which gRPC would
      // answer by closing its listener. The next connection to arrive wakes the listener again.
      errno = EAGAIN;
      return -1;
    }
  }
}
