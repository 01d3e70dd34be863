// CaptureGenerator: test captures made by the project, never downloaded. A walk
// around a COIL-100 object is rendered as a device would film it: the object's turntable views
// composited onto a cluttered, textured background that pans, the object's box drifting and
// scaling, some frames motion-blurred or noisy, and the device's orientation log at its own
// rate with noise and a slow drift. Everything is known: the true box and the view shown in
// each frame, the true azimuth of each log reading.
//
// Deterministic: equal options give equal captures (SeededRandom). Thread-safe.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "client/orientation_log.h"

namespace orbit {

struct CaptureGeneratorOptions {
  std::filesystem::path coil_dir;  // COIL-100's folder (objN__A.png)
  int object = 1;                  // COIL-100 object number, 1..100
  bool draw_object = true;         // false: the scene alone, as when the camera turned away
  cv::Size frame_size{320, 240};
  int frames = 72;
  double fps = 10;
  double start_azimuth_deg = 0;      // the view shown in the first frame (COIL's azimuths)
  double turn_deg = 360;             // how far the walk goes round, over all the frames
  int motion_period = 72;            // frames of one cycle of the pan, the drift and the scaling
  double box_fraction = 0.46;        // the object's square at scale 1, of the frame's height
  double log_rate_hz = 27;           // orientation readings per second (not the video's rate)
  double log_noise_deg = 3;          // deviation of each reading's noise
  double log_drift_deg_per_s = 0.4;  // slow drift of the device's compass
  double log_offset_deg = 40;        // the device's north against the model's
  int blur_every = 9;                // every n-th frame (n-1, 2n-1, ...) motion-blurred; 0: none
  int noise_every = 13;              // every n-th frame noisy (variance 0.01); 0: none
  std::uint64_t seed = 1;
};

struct GeneratedCapture {
  std::vector<cv::Mat> frames;          // BGR, frame_size, before encoding
  std::vector<cv::Rect> true_boxes;     // the object's bounding box in each frame
  std::vector<int> shown_azimuths;      // the COIL-100 view composited into each frame
  std::vector<bool> degraded;           // blurred or noisy on purpose
  std::vector<OrientationReading> log;  // timestamp_ms clock
  double fps = 0;
};

// Renders the capture. Throws std::runtime_error naming a COIL-100 file it cannot read.
GeneratedCapture GenerateCapture(const CaptureGeneratorOptions& options);

// Writes `capture` as a video (Motion-JPEG in AVI, readable by any OpenCV), its orientation log
// (CSV with header, docs/capture.md) and, when `boxes` is not empty, the true boxes (CSV
// `frame_index,x,y,w,h`). Throws std::runtime_error naming a file it cannot write.
void WriteCapture(const GeneratedCapture& capture, const std::filesystem::path& video,
                  const std::filesystem::path& log, const std::filesystem::path& boxes = {});

}  // namespace orbit
