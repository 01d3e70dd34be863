#include "core/base/parallel_for.h"

#include <sched.h>

#include <algorithm>
#include <atomic>
#include <exception>
#include <thread>
#include <vector>

#include "core/base/mutex.h"

namespace orbit {
namespace {

// What the threads of one ParallelFor share besides the next task's number.
struct Outcome {
  Mutex mutex;  // also serialises on_done
  std::exception_ptr error ABSL_GUARDED_BY(mutex);
  std::size_t done ABSL_GUARDED_BY(mutex) = 0;
};

}  // namespace

void ParallelFor(std::size_t count, int threads, const std::function<void(std::size_t)>& task,
                 const std::function<void(std::size_t done)>& on_done) {
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  Outcome outcome;
  const auto worker = [&] {
    while (!failed.load()) {
      const std::size_t i = next.fetch_add(1);
      if (i >= count) return;
      try {
        task(i);
      } catch (...) {
        MutexLock lock(&outcome.mutex);
        if (!outcome.error) outcome.error = std::current_exception();
        failed = true;
        return;
      }
      MutexLock lock(&outcome.mutex);
      ++outcome.done;
      if (on_done) on_done(outcome.done);
    }
  };
  const std::size_t wanted = static_cast<std::size_t>(std::max(threads, 1));
  const std::size_t extra = std::min(wanted, std::max<std::size_t>(count, 1)) - 1;
  std::vector<std::thread> pool;
  for (std::size_t t = 0; t < extra; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& thread : pool) thread.join();
  std::exception_ptr error;
  {
    MutexLock lock(&outcome.mutex);
    error = outcome.error;
  }
  if (error) std::rethrow_exception(error);
}

int AvailableCpus() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (::sched_getaffinity(0, sizeof(set), &set) == 0) return std::max(1, CPU_COUNT(&set));
  return std::max(1u, std::thread::hardware_concurrency());
}

}  // namespace orbit
