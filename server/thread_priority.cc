#include "server/thread_priority.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>

namespace orbit::server {

void LowerThisThreadsPriority(int steps) {
  if (steps <= 0) return;
  const auto thread = static_cast<id_t>(gettid());
  (void)setpriority(PRIO_PROCESS, thread, std::min(19, getpriority(PRIO_PROCESS, thread) + steps));
}

}  // namespace orbit::server
