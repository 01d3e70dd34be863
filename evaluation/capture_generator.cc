#include "evaluation/capture_generator.h"

#include <cmath>
#include <fstream>
#include <numbers>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "core/base/angles.h"
#include "core/base/seeded_random.h"
#include "core/descriptor/distortion.h"

namespace orbit {
namespace {

constexpr int kCoilStep = 5;             // COIL-100's views are 5 degrees apart
constexpr int kMaskThreshold = 24;       // COIL-100's black turntable: below this, background
constexpr double kNoiseVariance = 0.01;  // the noisy frames' Gaussian noise, [0, 1] scale

// A cluttered, textured scene larger than the frame, for the camera to pan over: a fine grain,
// then overlapping rectangles, discs and lines of every colour.
cv::Mat RenderBackground(cv::Size size, SeededRandom& random) {
  // The grain is drawn at a quarter of the resolution and enlarged, so that it is texture (a
  // few pixels across), not pixel noise the noise estimate would read.
  const cv::Size coarse(size.width / 4 + 1, size.height / 4 + 1);
  cv::Mat grain(coarse, CV_8UC3);
  for (int y = 0; y < coarse.height; ++y) {
    for (int x = 0; x < coarse.width; ++x) {
      const int level = 60 + static_cast<int>(random.UniformInt(120));
      grain.at<cv::Vec3b>(y, x) = cv::Vec3b(level, level, level);
    }
  }
  cv::Mat scene;
  cv::resize(grain, scene, size, 0, 0, cv::INTER_LINEAR);
  // Every draw is its own statement: the order in which a call's arguments are evaluated is
  // unspecified (GCC goes right to left on x86-64, left to right on ARM), so draws inside one
  // call's arguments would give another scene on another machine. The order below is the one
  // x86-64 builds have always drawn in, so their scenes stay as they were.
  auto colour = [&] {
    const double red = static_cast<double>(random.UniformInt(256));
    const double green = static_cast<double>(random.UniformInt(256));
    const double blue = static_cast<double>(random.UniformInt(256));
    return cv::Scalar(blue, green, red);
  };
  auto point = [&] {
    const int y = static_cast<int>(random.UniformInt(size.height));
    const int x = static_cast<int>(random.UniformInt(size.width));
    return cv::Point(x, y);
  };
  const int shapes = size.area() / 900;
  for (int s = 0; s < shapes; ++s) {
    switch (random.UniformInt(3)) {
      case 0: {
        const cv::Scalar fill = colour();
        const cv::Point corner = point();
        cv::rectangle(scene, point(), corner, fill, cv::FILLED);
        break;
      }
      case 1: {
        const cv::Scalar fill = colour();
        const int radius = 4 + static_cast<int>(random.UniformInt(30));
        cv::circle(scene, point(), radius, fill, cv::FILLED);
        break;
      }
      default: {
        const int thickness = 1 + static_cast<int>(random.UniformInt(4));
        const cv::Scalar ink = colour();
        const cv::Point end = point();
        cv::line(scene, point(), end, ink, thickness);
      }
    }
  }
  return scene;
}

cv::Mat ReadCoilView(const std::filesystem::path& dir, int object, int azimuth) {
  const std::filesystem::path file =
      dir / ("obj" + std::to_string(object) + "__" + std::to_string(azimuth) + ".png");
  cv::Mat image = cv::imread(file.string(), cv::IMREAD_COLOR);
  if (image.empty()) throw std::runtime_error("cannot read COIL-100 view " + file.string());
  return image;
}

// The device's azimuth reading of the true azimuth `azimuth` at `seconds` into the walk.
double DeviceAzimuth(const CaptureGeneratorOptions& options, double azimuth, double seconds,
                     SeededRandom& random) {
  return NormaliseAzimuth(azimuth + options.log_offset_deg + options.log_drift_deg_per_s * seconds +
                          options.log_noise_deg * random.Normal());
}

}  // namespace

GeneratedCapture GenerateCapture(const CaptureGeneratorOptions& options) {
  if (options.frames < 1 || !(options.fps > 0) || !(options.log_rate_hz > 0) ||
      options.motion_period < 1) {
    throw std::invalid_argument(
        "a generated capture needs frames >= 1, fps > 0, log rate > 0, motion period >= 1");
  }
  SeededRandom random(MixSeed(options.seed, static_cast<std::uint64_t>(options.object)));
  const cv::Size frame = options.frame_size;
  const cv::Mat scene = RenderBackground(cv::Size(frame.width * 2, frame.height * 2), random);

  GeneratedCapture capture;
  capture.fps = options.fps;
  const double n = options.frames;
  for (int i = 0; i < options.frames; ++i) {
    const double azimuth = options.start_azimuth_deg + options.turn_deg * i / n;
    const double t = static_cast<double>(i % options.motion_period) / options.motion_period;
    const int shown =
        static_cast<int>(std::lround(NormaliseAzimuth(azimuth) / kCoilStep)) * kCoilStep % 360;
    // The camera pans over the scene while the object drifts in the frame and its apparent
    // size breathes by +-10% (the walker's distance changes).
    const cv::Point pan(
        static_cast<int>(frame.width / 2 * (1 + std::sin(2 * std::numbers::pi * t))),
        static_cast<int>(frame.height / 2 * (1 - std::cos(2 * std::numbers::pi * t))));
    cv::Mat image = scene(cv::Rect(pan, frame)).clone();
    const double scale = 1 + 0.1 * std::sin(2 * std::numbers::pi * t);
    const int side = static_cast<int>(std::lround(options.box_fraction * frame.height * scale));
    const cv::Point2d centre(frame.width * (0.5 + 0.18 * std::sin(2 * std::numbers::pi * t)),
                             frame.height * (0.5 + 0.12 * std::cos(2 * std::numbers::pi * t)));
    cv::Rect square(static_cast<int>(std::lround(centre.x - side / 2.0)),
                    static_cast<int>(std::lround(centre.y - side / 2.0)), side, side);
    square &= cv::Rect(0, 0, frame.width, frame.height);

    cv::Mat view;
    cv::resize(ReadCoilView(options.coil_dir, options.object, shown), view, square.size(), 0, 0,
               cv::INTER_AREA);
    cv::Mat grey, mask;
    cv::cvtColor(view, grey, cv::COLOR_BGR2GRAY);
    cv::threshold(grey, mask, kMaskThreshold, 255, cv::THRESH_BINARY);
    cv::morphologyEx(mask, mask, cv::MORPH_OPEN, cv::Mat());
    if (options.draw_object) view.copyTo(image(square), mask);
    cv::Rect object = cv::boundingRect(mask);
    object.x += square.x;
    object.y += square.y;

    bool degraded = false;
    if (options.blur_every > 0 && i % options.blur_every == options.blur_every - 1) {
      image = MotionBlur(image);
      degraded = true;
    } else if (options.noise_every > 0 && i % options.noise_every == options.noise_every - 1) {
      image = AddGaussianNoise(image, kNoiseVariance, MixSeed(options.seed, 1000 + i));
      degraded = true;
    }
    capture.frames.push_back(image);
    capture.true_boxes.push_back(object);
    capture.shown_azimuths.push_back(shown);
    capture.degraded.push_back(degraded);
  }

  // Readings from before the first frame to after the last, at the log's own rate with a
  // little jitter, each of the true azimuth at its time.
  const double period_ms = 1000 / options.log_rate_hz;
  // The last reading falls after the last frame whatever its jitter.
  const double end_ms = (options.frames - 1) * 1000 / options.fps + 2 * period_ms;
  for (double t = 0; t <= end_ms; t += period_ms) {
    const double at = t == 0 ? 0 : t + period_ms * 0.3 * (random.Uniform() - 0.5);
    const double walk = at / 1000 * options.fps / n;  // the walk's progress, as the frames'
    OrientationReading reading;
    reading.time = at;
    reading.azimuth_deg = DeviceAzimuth(
        options, options.start_azimuth_deg + options.turn_deg * walk, at / 1000, random);
    capture.log.push_back(reading);
  }
  return capture;
}

void WriteCapture(const GeneratedCapture& capture, const std::filesystem::path& video,
                  const std::filesystem::path& log, const std::filesystem::path& boxes) {
  if (capture.frames.empty()) throw std::invalid_argument("a capture without frames");
  // FFmpeg's Motion-JPEG encoder: OpenCV's own (CAP_OPENCV_MJPEG) writes an occasional frame
  // that decoders report as corrupt.
  cv::VideoWriter writer(video.string(), cv::CAP_FFMPEG,
                         cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), capture.fps,
                         capture.frames.front().size());
  if (!writer.isOpened()) throw std::runtime_error("cannot write video " + video.string());
  for (const cv::Mat& frame : capture.frames) writer.write(frame);
  writer.release();

  std::ofstream log_out(log);
  log_out.precision(10);
  log_out << "timestamp_ms,azimuth_deg\n";
  for (const OrientationReading& r : capture.log) log_out << r.time << "," << r.azimuth_deg << "\n";
  if (!log_out) throw std::runtime_error("cannot write orientation log " + log.string());

  if (boxes.empty()) return;
  std::ofstream box_out(boxes);
  box_out << "frame_index,x,y,w,h\n";
  for (std::size_t f = 0; f < capture.true_boxes.size(); ++f) {
    const cv::Rect& b = capture.true_boxes[f];
    box_out << f << "," << b.x << "," << b.y << "," << b.width << "," << b.height << "\n";
  }
  if (!box_out) throw std::runtime_error("cannot write boxes " + boxes.string());
}

}  // namespace orbit
