#include "cli/capture_selection_text.h"

#include <cstdio>
#include <sstream>
#include <vector>

namespace orbit::cli {
namespace {

// `value` in degrees as the lines above write an azimuth: one decimal.
std::string Degrees(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", value);
  return text;
}

// A step's bound or size as given: "25", "7.5".
std::string Bound(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

// "1 frame", "3 frames".
std::string Count(long n, const std::string& thing) {
  return std::to_string(n) + " " + thing + (n == 1 ? "" : "s");
}

// Why `step` has no view: no frame, or what became of its frames. A step's frames that were
// neither lost nor too noisy were all too blurred, since its sharpest one was
// (client/capture_views.h).
std::string NoViewReason(const CaptureStep& step) {
  if (step.frames == 0) return "no frame (the walk did not pass here)";
  std::vector<std::string> parts;
  const long blurred = step.frames - step.lost - step.noisy;
  if (blurred > 0) parts.push_back(std::to_string(blurred) + " too blurred");
  if (step.lost > 0) parts.push_back(std::to_string(step.lost) + " lost by the tracker");
  if (step.noisy > 0) parts.push_back(std::to_string(step.noisy) + " too noisy");
  if (step.frames == 1) return "1 frame," + parts.front().substr(1);
  std::string text = Count(step.frames, "frame") + ": ";
  for (std::size_t i = 0; i < parts.size(); ++i) text += (i > 0 ? ", " : "") + parts[i];
  return text;
}

}  // namespace

std::string CaptureSelectionText(const CaptureViewSelection& selection, double step_deg) {
  std::ostringstream text;
  text << "  capture: " << selection.frames_read << " frames, " << selection.frames_lost
       << " lost, " << selection.frames_unusable << " too blurred or noisy; views in "
       << selection.views.size() << " of " << selection.steps_total << " steps of "
       << Bound(step_deg) << " degrees\n";
  for (const CaptureStep& step : selection.steps) {
    text << "  step " << Bound(step.from_deg) << "-" << Bound(step.to_deg) << ": ";
    if (step.view) {
      const CaptureView& view = selection.views[*step.view];
      text << "frame " << view.frame_index << " at " << Degrees(view.image.azimuth_deg)
           << " degrees\n";
    } else {
      text << "no view: " << NoViewReason(step) << "\n";
    }
  }
  // A view may lie anywhere in its step, so arcs up to two steps wide are listed too: the views
  // the operator asked for (one per step) are not there.
  if (selection.gaps.size() == 1 && selection.gaps.front().width() >= 360) {
    text << "  gaps: one view only, at " << Degrees(selection.gaps.front().from)
         << " degrees: walk all round the object, slowly, keeping it in the box\n";
  } else if (!selection.gaps.empty()) {
    text << "  gaps: " << selection.gaps.size() << " arcs between views wider than the step of "
         << Bound(step_deg) << " degrees: ";
    for (std::size_t i = 0; i < selection.gaps.size(); ++i) {
      const AzimuthGap& gap = selection.gaps[i];
      text << (i > 0 ? ", " : "") << Degrees(gap.from) << "-" << Degrees(gap.to) << " ("
           << Degrees(gap.width()) << ")";
    }
    text << ": walk those arcs again slowly, keeping the object in the box, or give a smaller "
            "--step\n";
  }
  return text.str();
}

}  // namespace orbit::cli
