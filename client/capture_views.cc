#include "client/capture_views.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "core/base/angles.h"

namespace orbit {

CaptureViewSelection SelectCaptureViews(CaptureReader& capture, const CaptureViewOptions& options) {
  if (!(options.step_deg > 0 && options.step_deg <= 180)) {
    throw std::invalid_argument("azimuth step must be in (0, 180] degrees");
  }
  CaptureViewSelection selection;
  selection.steps_total = static_cast<int>(std::ceil(360 / options.step_deg - 1e-9));
  // The sharpest tracked, not-too-noisy frame of each step so far, and every tracked frame's
  // quality for the capture's median sharpness.
  std::map<int, CaptureView> best;
  std::vector<FrameQuality> qualities;
  VideoFrame frame;
  while (capture.Next(frame)) {
    ++selection.frames_read;
    if (options.progress) options.progress(selection.frames_read, capture.frame_count());
    if (frame.lost) {
      ++selection.frames_lost;
      continue;
    }
    qualities.push_back(frame.quality);
    if (!IsUsableFrame(frame.quality, 0, options.quality)) {  // too noisy
      ++selection.frames_unusable;
      continue;
    }
    const int step =
        std::min(selection.steps_total - 1,
                 static_cast<int>(std::floor(frame.orientation.azimuth_deg / options.step_deg)));
    auto [it, inserted] = best.try_emplace(step);
    if (inserted || frame.quality.sharpness > it->second.quality.sharpness) {
      it->second = CaptureView{
          frame.index, frame.region, frame.quality,
          EnrollmentImage{frame.image(frame.region).clone(), frame.orientation.azimuth_deg,
                          std::nullopt, frame.orientation.elevation_deg}};
    }
  }
  // A step's sharpest frame below the usable sharpness means every frame of the step is.
  const double min_sharpness = MinUsableSharpness(qualities, options.quality);
  for (auto& [step, view] : best) {
    if (!IsUsableFrame(view.quality, min_sharpness, options.quality)) {
      ++selection.frames_unusable;
      continue;
    }
    selection.views.push_back(std::move(view));
  }
  std::sort(
      selection.views.begin(), selection.views.end(),
      [](const CaptureView& a, const CaptureView& b) { return a.frame_index < b.frame_index; });
  return selection;
}

}  // namespace orbit
