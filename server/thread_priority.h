// Lowering a thread's CPU priority, for the server's background work (image decoding,
// enrollments, recalibration) so that a session's descriptor frame gets the core at once.
#pragma once

namespace orbit::server {

// Makes the calling thread `steps` nicer (Linux keeps a nice value per thread; capped at 19).
// Only lowers the priority, which needs no privilege; a failure leaves it as it was.
void LowerThisThreadsPriority(int steps);

// Puts the calling thread in Linux's SCHED_IDLE class: it runs on a core's idle time, and any
// other thread waking up takes the core from it at once (a nice value only shifts shares and
// deadlines). For work nobody waits for. Falls back to nice 19 where the class is refused;
// returns whether SCHED_IDLE was set.
bool RunThisThreadOnIdleTime();

}  // namespace orbit::server
