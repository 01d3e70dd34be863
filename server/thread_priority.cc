#include "server/thread_priority.h"

#include <sched.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>

namespace orbit::server {

void LowerThisThreadsPriority(int steps) {
  if (steps <= 0) return;
  const auto thread = static_cast<id_t>(gettid());
  (void)setpriority(PRIO_PROCESS, thread, std::min(19, getpriority(PRIO_PROCESS, thread) + steps));
}

bool RunThisThreadOnIdleTime() {
  const sched_param parameters{.sched_priority = 0};
  if (sched_setscheduler(0, SCHED_IDLE, &parameters) == 0) return true;  // 0: this thread
  LowerThisThreadsPriority(19);
  return false;
}

}  // namespace orbit::server
