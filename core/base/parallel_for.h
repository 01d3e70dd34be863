// ParallelFor: the one worker fan-out of the product, for work that splits into independent
// tasks (describing the views of an enrollment, an import's images, an evaluation's trials).
//
//   ParallelFor(images.size(), threads, [&](std::size_t i) { views[i] = Describe(images[i]); });
//
// Thread safety: may be called from any thread; it starts and joins its own.
#pragma once

#include <cstddef>
#include <functional>

namespace orbit {

// Runs task(i) once for every i in [0, count) on at most `threads` threads, the calling thread
// among them (threads < 1 counts as 1). Tasks are handed out in increasing i as threads free up.
// After each task that returns, `on_done(tasks done so far)` is called, never concurrently (may
// be empty). When a task throws, tasks not yet started are skipped and, once every thread has
// stopped, the first exception thrown is rethrown unchanged.
void ParallelFor(std::size_t count, int threads, const std::function<void(std::size_t)>& task,
                 const std::function<void(std::size_t done)>& on_done = {});

// The number of CPUs this process may run on (its affinity mask), at least 1.
int AvailableCpus();

}  // namespace orbit
