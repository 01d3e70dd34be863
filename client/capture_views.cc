#include "client/capture_views.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "core/base/angles.h"

namespace orbit {
namespace {

// The step of `azimuth_deg` (in [0, 360), as the log gives it): [k * step, (k + 1) * step).
std::size_t StepOf(double azimuth_deg, double step_deg, int steps_total) {
  return static_cast<std::size_t>(
      std::clamp(static_cast<int>(std::floor(azimuth_deg / step_deg)), 0, steps_total - 1));
}

}  // namespace

CaptureViewSelection SelectCaptureViews(CaptureReader& capture, const CaptureViewOptions& options) {
  if (!(options.step_deg > 0 && options.step_deg <= 180)) {
    throw std::invalid_argument("azimuth step must be in (0, 180] degrees");
  }
  CaptureViewSelection selection;
  selection.steps_total = static_cast<int>(std::ceil(360 / options.step_deg - 1e-9));
  for (int k = 0; k < selection.steps_total; ++k) {
    selection.steps.push_back({k * options.step_deg, std::min(360.0, (k + 1) * options.step_deg)});
  }
  // The sharpest tracked, not-too-noisy frame of each step so far, and every tracked frame's
  // quality for the capture's median sharpness.
  std::map<std::size_t, CaptureView> best;
  std::vector<FrameQuality> qualities;
  VideoFrame frame;
  while (capture.Next(frame)) {
    ++selection.frames_read;
    if (options.progress) options.progress(selection.frames_read, capture.frame_count());
    const std::size_t step =
        StepOf(frame.orientation.azimuth_deg, options.step_deg, selection.steps_total);
    CaptureStep& counts = selection.steps[step];
    ++counts.frames;
    if (frame.lost) {
      ++selection.frames_lost;
      ++counts.lost;
      continue;
    }
    qualities.push_back(frame.quality);
    if (!IsUsableFrame(frame.quality, 0, options.quality)) {  // too noisy
      ++selection.frames_unusable;
      ++counts.noisy;
      continue;
    }
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
  std::vector<double> azimuths;
  for (std::size_t v = 0; v < selection.views.size(); ++v) {
    const double azimuth = selection.views[v].image.azimuth_deg;
    azimuths.push_back(azimuth);
    selection.steps[StepOf(azimuth, options.step_deg, selection.steps_total)].view = v;
  }
  selection.gaps = AzimuthGaps(std::move(azimuths), options.step_deg);
  return selection;
}

}  // namespace orbit
