#include "evaluation/synthetic_object.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

#include "core/base/seeded_random.h"

namespace orbit {
namespace {

constexpr int kTexture = 256;       // side of a face texture, pixels
constexpr double kHalfWidth = 0.8;  // box half-width, cylinder radius
constexpr double kHalfHeight = 1.0;
constexpr double kCameraDistance = 5;  // from the object's centre
constexpr double kElevationDeg = 20;   // the camera looks slightly down
constexpr double kHalfFieldDeg = 18;
constexpr int kSupersampling = 2;  // rendered at twice the size, then averaged down

// --- Face textures -----------------------------------------------------------------------

cv::Mat Stripes(cv::Scalar a, cv::Scalar b, int period, double angle_deg) {
  cv::Mat t(kTexture, kTexture, CV_8UC3);
  const double c = std::cos(angle_deg * std::numbers::pi / 180);
  const double s = std::sin(angle_deg * std::numbers::pi / 180);
  for (int y = 0; y < kTexture; ++y) {
    for (int x = 0; x < kTexture; ++x) {
      const double along = x * c + y * s;
      const bool first = static_cast<int>(std::floor(along / period)) % 2 == 0;
      const cv::Scalar& colour = first ? a : b;
      t.at<cv::Vec3b>(y, x) = cv::Vec3b(colour[0], colour[1], colour[2]);
    }
  }
  return t;
}

cv::Mat Checker(cv::Scalar a, cv::Scalar b, int cell) {
  cv::Mat t(kTexture, kTexture, CV_8UC3, a);
  for (int y = 0; y < kTexture; y += cell) {
    for (int x = (y / cell) % 2 == 0 ? cell : 0; x < kTexture; x += 2 * cell) {
      cv::rectangle(t, cv::Rect(x, y, cell, cell), b, cv::FILLED);
    }
  }
  return t;
}

cv::Mat Dots(cv::Scalar background, cv::Scalar dot, int spacing, int radius) {
  cv::Mat t(kTexture, kTexture, CV_8UC3, background);
  for (int y = spacing / 2; y < kTexture; y += spacing) {
    for (int x = spacing / 2; x < kTexture; x += spacing) {
      cv::circle(t, {x, y}, radius, dot, cv::FILLED, cv::LINE_AA);
    }
  }
  return t;
}

cv::Mat Rings(cv::Scalar background, cv::Scalar ring, int spacing) {
  cv::Mat t(kTexture, kTexture, CV_8UC3, background);
  for (int r = spacing; r < kTexture; r += spacing) {
    cv::circle(t, {kTexture / 2, kTexture / 2}, r, ring, spacing / 3, cv::LINE_AA);
  }
  return t;
}

cv::Mat Zigzag(cv::Scalar background, cv::Scalar line, int step) {
  cv::Mat t(kTexture, kTexture, CV_8UC3, background);
  for (int y = step; y < kTexture; y += 2 * step) {
    std::vector<cv::Point> points;
    for (int x = 0; x <= kTexture; x += step) {
      points.emplace_back(x, y + ((x / step) % 2 ? step : 0));
    }
    cv::polylines(t, points, false, line, step / 3, cv::LINE_AA);
  }
  return t;
}

cv::Mat Label(cv::Scalar background, cv::Scalar ink, const std::string& text) {
  cv::Mat t(kTexture, kTexture, CV_8UC3, background);
  cv::rectangle(t, cv::Rect(12, 12, kTexture - 24, kTexture - 24), ink, 8);
  int baseline = 0;
  const double scale = 2.2;
  const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_DUPLEX, scale, 6, &baseline);
  cv::putText(t, text, {(kTexture - size.width) / 2, (kTexture + size.height) / 2},
              cv::FONT_HERSHEY_DUPLEX, scale, ink, 6, cv::LINE_AA);
  return t;
}

// Four panels side by side: a label wrapped around a cylinder.
cv::Mat Wrap(const std::array<cv::Mat, 4>& panels) {
  cv::Mat wide;
  cv::hconcat(std::vector<cv::Mat>(panels.begin(), panels.end()), wide);
  cv::Mat label;
  cv::resize(wide, label, cv::Size(2 * kTexture, kTexture), 0, 0, cv::INTER_AREA);
  return label;
}

// --- Ray casting -------------------------------------------------------------------------

constexpr int kLid = ViewRays::kLid;

struct Hit {
  double distance;
  cv::Vec3d normal;  // object coordinates
  int surface;       // 0-3: faces[surface] at (u, v); kLid: top_colour
  double u = 0, v = 0;
};

cv::Vec3b Sample(const cv::Mat& texture, double u, double v) {
  const int x = std::clamp(static_cast<int>(u * texture.cols), 0, texture.cols - 1);
  const int y = std::clamp(static_cast<int>(v * texture.rows), 0, texture.rows - 1);
  return texture.at<cv::Vec3b>(y, x);
}

cv::Vec3b Colour(cv::Scalar s) {
  return cv::Vec3b(static_cast<uchar>(s[0]), static_cast<uchar>(s[1]), static_cast<uchar>(s[2]));
}

// The nearest face of the box [-a, a] x [-h, h] x [-a, a] that the ray o + t d enters.
std::optional<Hit> HitBox(cv::Vec3d o, cv::Vec3d d) {
  const cv::Vec3d half(kHalfWidth, kHalfHeight, kHalfWidth);
  double enter = -1e300, leave = 1e300;
  int axis = -1;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-12) {
      if (std::abs(o[k]) > half[k]) return std::nullopt;
      continue;
    }
    double t0 = (-half[k] - o[k]) / d[k], t1 = (half[k] - o[k]) / d[k];
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > enter) {
      enter = t0;
      axis = k;
    }
    leave = std::min(leave, t1);
  }
  if (axis < 0 || enter > leave || enter <= 0) return std::nullopt;
  const cv::Vec3d p = o + enter * d;
  cv::Vec3d n(0, 0, 0);
  n[axis] = d[axis] < 0 ? 1 : -1;
  if (axis == 1) return Hit{enter, n, kLid};
  // Side faces in order around the box: +z, +x, -z, -x; u runs counter-clockwise seen from above.
  const double v = (kHalfHeight - p[1]) / (2 * kHalfHeight);
  const double width = 2 * kHalfWidth;
  int face = 3;
  double u = (p[2] + kHalfWidth) / width;
  if (axis == 2 && n[2] > 0) {
    face = 0;
    u = (p[0] + kHalfWidth) / width;
  } else if (axis == 0 && n[0] > 0) {
    face = 1;
    u = (kHalfWidth - p[2]) / width;
  } else if (axis == 2) {
    face = 2;
    u = (kHalfWidth - p[0]) / width;
  }
  return Hit{enter, n, face, u, v};
}

// The cylinder x^2 + z^2 <= r^2, |y| <= h: its side (the label) or its lid.
std::optional<Hit> HitCylinder(cv::Vec3d o, cv::Vec3d d) {
  const double r = kHalfWidth;
  const double a = d[0] * d[0] + d[2] * d[2];
  const double b = 2 * (o[0] * d[0] + o[2] * d[2]);
  const double c = o[0] * o[0] + o[2] * o[2] - r * r;
  const double disc = b * b - 4 * a * c;
  if (a > 1e-12 && disc >= 0) {
    const double t = (-b - std::sqrt(disc)) / (2 * a);
    const cv::Vec3d p = o + t * d;
    if (t > 0 && std::abs(p[1]) <= kHalfHeight) {
      const double u = (std::atan2(p[0], p[2]) + std::numbers::pi) / (2 * std::numbers::pi);
      const double v = (kHalfHeight - p[1]) / (2 * kHalfHeight);
      return Hit{t, cv::Vec3d(p[0] / r, 0, p[2] / r), 0, u, v};
    }
  }
  if (std::abs(d[1]) > 1e-12) {
    const double t = (kHalfHeight - o[1]) / d[1];
    const cv::Vec3d p = o + t * d;
    if (t > 0 && p[0] * p[0] + p[2] * p[2] <= r * r) {
      return Hit{t, cv::Vec3d(0, 1, 0), kLid};
    }
  }
  return std::nullopt;
}

cv::Vec3d RotateY(cv::Vec3d v, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return cv::Vec3d(c * v[0] + s * v[2], v[1], -s * v[0] + c * v[2]);
}

}  // namespace

std::vector<SyntheticObject> DemoObjects() {
  const cv::Scalar red(40, 40, 220), white(245, 245, 245), blue(200, 90, 30), yellow(40, 220, 240),
      green(60, 170, 40), orange(30, 140, 250), black(20, 20, 20), magenta(200, 40, 200),
      cyan(220, 210, 40), navy(90, 30, 20), purple(140, 40, 110), grey(150, 150, 150),
      teal(140, 130, 0);
  std::vector<SyntheticObject> objects(3);
  objects[0].name = "demo-box";
  objects[0].shape = SyntheticObject::Shape::kBox;
  objects[0].faces = {Stripes(red, white, 24, 45), Checker(blue, yellow, 32),
                      Dots(green, white, 42, 12), Label(orange, black, "ORBIT")};
  objects[0].top_colour = grey;

  objects[1].name = "demo-can";
  objects[1].shape = SyntheticObject::Shape::kCylinder;
  objects[1].faces = {Wrap({Stripes(magenta, white, 20, 0), Rings(cyan, navy, 24),
                            Dots(navy, yellow, 36, 10), Label(white, red, "CAN")}),
                      cv::Mat(), cv::Mat(), cv::Mat()};
  objects[1].top_colour = cv::Scalar(190, 190, 190);

  objects[2].name = "demo-crate";
  objects[2].shape = SyntheticObject::Shape::kBox;
  objects[2].faces = {Stripes(purple, grey, 28, 90), Checker(black, white, 16),
                      Zigzag(yellow, blue, 24), Label(teal, white, "42")};
  objects[2].top_colour = cv::Scalar(60, 100, 140);
  return objects;
}

SyntheticObject RandomSyntheticObject(std::uint64_t seed, std::string name) {
  SeededRandom random(MixSeed(seed, 0x6f626a656374ULL /* "object" */));
  const auto uniform = [&](int low, int high) {  // an integer in [low, high]
    return low + static_cast<int>(random.UniformInt(static_cast<std::uint64_t>(high - low + 1)));
  };
  const auto colour = [&] { return cv::Scalar(uniform(0, 255), uniform(0, 255), uniform(0, 255)); };
  const auto pattern = [&] {
    const cv::Scalar a = colour(), b = colour();
    switch (uniform(0, 4)) {
      case 0: return Stripes(a, b, uniform(8, 48), uniform(0, 179));
      case 1: return Checker(a, b, uniform(8, 64));
      case 2: return Dots(a, b, uniform(20, 64), uniform(4, 9));
      case 3: return Rings(a, b, uniform(12, 48));
      default: return Zigzag(a, b, uniform(12, 40));
    }
  };
  SyntheticObject object;
  object.name = std::move(name);
  object.shape =
      uniform(0, 1) == 0 ? SyntheticObject::Shape::kBox : SyntheticObject::Shape::kCylinder;
  if (object.shape == SyntheticObject::Shape::kBox) {
    for (cv::Mat& face : object.faces) face = pattern();
  } else {
    object.faces = {Wrap({pattern(), pattern(), pattern(), pattern()}), cv::Mat(), cv::Mat(),
                    cv::Mat()};
  }
  object.top_colour = colour();
  return object;
}

ViewRays CastViewRays(SyntheticObject::Shape shape, double azimuth_deg, int size) {
  ViewRays rays;
  rays.shape = shape;
  rays.size = size;
  const int big = size * kSupersampling;
  const double elevation = kElevationDeg * std::numbers::pi / 180;
  const double azimuth = azimuth_deg * std::numbers::pi / 180;
  const double focal = (big / 2.0) / std::tan(kHalfFieldDeg * std::numbers::pi / 180);
  // The camera orbits the object by -azimuth: the object turns by +azimuth in its view.
  const cv::Vec3d eye = RotateY(
      cv::Vec3d(0, kCameraDistance * std::sin(elevation), kCameraDistance * std::cos(elevation)),
      -azimuth);
  const cv::Vec3d forward = cv::normalize(-eye);
  const cv::Vec3d right = cv::normalize(forward.cross(cv::Vec3d(0, 1, 0)));
  const cv::Vec3d up = right.cross(forward);
  for (int row = 0; row < big; ++row) {
    for (int col = 0; col < big; ++col) {
      const double x = (col + 0.5 - big / 2.0) / focal;
      const double y = -(row + 0.5 - big / 2.0) / focal;
      const cv::Vec3d ray = cv::normalize(forward + x * right + y * up);
      const std::optional<Hit> hit =
          shape == SyntheticObject::Shape::kBox ? HitBox(eye, ray) : HitCylinder(eye, ray);
      if (!hit) continue;
      // Lit from the camera: faces turned away are darker, as on a turntable with a key light.
      const double light = 0.35 + 0.65 * std::max(0.0, -hit->normal.dot(ray));
      rays.hits.push_back({row * big + col, hit->surface, hit->u, hit->v, light});
    }
  }
  return rays;
}

cv::Mat RenderView(const SyntheticObject& object, const ViewRays& rays) {
  if (rays.shape != object.shape) {
    throw std::invalid_argument("RenderView: rays cast for another shape than " + object.name +
                                "'s");
  }
  const int big = rays.size * kSupersampling;
  cv::Mat image(big, big, CV_8UC3, cv::Scalar(0, 0, 0));
  auto* pixels = image.ptr<cv::Vec3b>(0);  // continuous: allocated whole
  const cv::Vec3b lid = Colour(object.top_colour);
  for (const ViewRays::Hit& hit : rays.hits) {
    const cv::Vec3b colour =
        hit.surface == kLid ? lid : Sample(object.faces[hit.surface], hit.u, hit.v);
    cv::Vec3b& pixel = pixels[hit.pixel];
    for (int k = 0; k < 3; ++k) pixel[k] = cv::saturate_cast<uchar>(colour[k] * hit.light);
  }
  cv::Mat view;
  cv::resize(image, view, cv::Size(rays.size, rays.size), 0, 0, cv::INTER_AREA);
  return view;
}

cv::Mat RenderView(const SyntheticObject& object, double azimuth_deg, int size) {
  return RenderView(object, CastViewRays(object.shape, azimuth_deg, size));
}

}  // namespace orbit
