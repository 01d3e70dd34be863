// The enrollment report (core/decision/enrollment_feedback.h, v1::EnrollmentReport) as `orbit
// enroll` and `orbit import` print it under each enrolled object: indented lines an operator acts
// on.
//
//   coverage: 2 gaps wider than 30 degrees: 100-180 (80), 300-20 (80)
//   repeats: 3 views add nothing (at 90, 180, 270 degrees)
//   confusable: obj42 (similarity 0.953, 3 views closer than its own), obj9 (0.912), ...
#pragma once

#include <string>

#include "orbit/v1/types.pb.h"

namespace orbit::cli {

// The lines above, each ending in "\n"; "" for a report with no gaps, repeats or objects.
std::string EnrollmentReportText(const v1::EnrollmentReport& report);

}  // namespace orbit::cli
