// Lowering a thread's CPU priority, for the server's background work (image decoding,
// enrollments, recalibration) so that a session's descriptor frame gets the core at once.
#pragma once

namespace orbit::server {

// Makes the calling thread `steps` nicer (Linux keeps a nice value per thread; capped at 19).
// Only lowers the priority, which needs no privilege; a failure leaves it as it was.
void LowerThisThreadsPriority(int steps);

}  // namespace orbit::server
