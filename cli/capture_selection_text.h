// What `orbit enroll --video` tells the operator about the views it took from a walk
// (client/capture_views.h), above the server's report: how many frames were read, lost or
// unusable; for every step of the circle the frame kept or why none was; and where the views
// kept leave an arc wider than the step, with what to capture there.
//
//   capture: 7 frames, 0 lost, 2 too blurred or noisy; views in 5 of 15 steps of 25 degrees
//   step 0-25: frame 0 at 5.0 degrees
//   step 25-50: frame 1 at 40.0 degrees
//   step 50-75: no view: no frame (the walk did not pass here)
//   step 75-100: frame 2 at 83.0 degrees
//   step 100-125: no view: 4 frames: 3 too blurred, 1 lost by the tracker
//   ...
//   gaps: 4 arcs between views wider than the step of 25 degrees: 5.0-40.0 (35.0), 40.0-83.0
//     (43.0), 83.0-160.0 (77.0), 185.0-5.0 (180.0): walk those arcs again slowly, keeping the
//     object in the box, or give a smaller --step
#pragma once

#include <string>

#include "client/capture_views.h"

namespace orbit::cli {

// The lines above for `selection`, made with steps of `step_deg` degrees, each indented by two
// spaces and ending in "\n": the capture line, one line per step, and the gaps line when the
// views leave an arc wider than the step (one view alone: the whole circle).
std::string CaptureSelectionText(const CaptureViewSelection& selection, double step_deg);

}  // namespace orbit::cli
