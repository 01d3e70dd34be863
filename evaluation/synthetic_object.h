// SyntheticObject: textured shapes `orbit demo` renders itself, so a new user sees recognition
// work without any dataset. Each object looks different from every side - a box whose four
// faces carry different patterns, a cylinder wrapped in a label that changes around it - so
// its appearance, like a real object's, depends on the azimuth it is seen from.
//
// Views are rendered like COIL-100's turntable images: the object centred on black, lit from
// the camera, seen slightly from above, at any azimuth (degrees, the object turning
// counter-clockwise seen from above as the azimuth grows). Pure and thread-safe.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace orbit {

struct SyntheticObject {
  enum class Shape { kBox, kCylinder };
  std::string name;
  Shape shape = Shape::kBox;
  // kBox: the four side faces in order around the box (square textures).
  // kCylinder: faces[0] is the label wrapped once around it (twice as wide as tall).
  std::array<cv::Mat, 4> faces;
  cv::Scalar top_colour;  // BGR of the lid seen from above
};

// The demo's objects: "demo-box", "demo-can", "demo-crate", with fixed textures.
std::vector<SyntheticObject> DemoObjects();

// An object drawn from `seed` alone: a box or a cylinder, each face (or the label's four panels)
// a pattern of stripes, checks, dots, rings or zigzags in two random colours with random sizes
// and angles, and a random lid. Different seeds give objects that differ in colour and pattern
// from every side; the same seed gives the same object on every platform.
SyntheticObject RandomSyntheticObject(std::uint64_t seed, std::string name);

// The object seen from `azimuth_deg`, as a `size` x `size` BGR image (CV_8UC3): its rays cast
// (CastViewRays) and painted (RenderView below).
cv::Mat RenderView(const SyntheticObject& object, double azimuth_deg, int size = 128);

// What the rays of one view hit, whatever the textures. Every object of one shape has the same
// geometry (only its textures and lid colour are its own), so a caller that renders many objects
// (MakeDistractors) casts each shape's rays once per azimuth and paints every object with them:
// the same pixels as RenderView(object, azimuth, size), for a fraction of the work.
struct ViewRays {
  static constexpr int kLid = 4;  // a hit's surface when it sees the lid
  struct Hit {
    int pixel;     // row-major, in the supersampled image
    int surface;   // 0-3: the object's faces[surface] at (u, v); kLid: its lid
    double u, v;   // texture coordinates in [0, 1]
    double light;  // the shading factor
  };
  SyntheticObject::Shape shape = SyntheticObject::Shape::kBox;
  int size = 0;           // the view's side, pixels
  std::vector<Hit> hits;  // the pixels that see the object, in row-major order
};
ViewRays CastViewRays(SyntheticObject::Shape shape, double azimuth_deg, int size = 128);

// `object` painted along `rays`. Throws std::invalid_argument when the rays were cast for
// another shape.
cv::Mat RenderView(const SyntheticObject& object, const ViewRays& rays);

}  // namespace orbit
