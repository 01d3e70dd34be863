// The object's region: the part of an image that is described when the object's box is known
// (docs/design.md#object-region). One definition for every path that cuts a box out of an
// image: a device describing its frames, `orbit enroll` and `orbit recognize` with --box or
// --boxes, `orbit import --boxes` and `orbit eval --boxes`, so that the same image, box and
// margin are described as the same pixels whichever path takes them.
#pragma once

#include <string_view>

#include <opencv2/core.hpp>

namespace orbit {

// The share of a box's width added on its left and on its right, and of its height above and
// below, unless a command is told otherwise (--box-margin): a little of the object's outline
// and surroundings, which a tight annotator's or tracker's box would cut off.
inline constexpr double kDefaultBoxMargin = 0.1;

// Throws std::invalid_argument "box margin must be in 0..1, got M" unless 0 <= margin <= 1.
void CheckBoxMargin(double margin);

// The region of an image of size `image` that describes the object in `box`: the box grown by
// round(margin * width) pixels on the left and on the right and round(margin * height) above
// and below, then clipped to the image. The box itself must lie inside the image: x, y >= 0,
// w, h >= 1, x + w <= the image's width, y + h <= its height.
//
// Throws std::invalid_argument, as CheckBoxMargin does, and for a box that is empty or not
// inside the image: "ORIGIN: RULE", where `origin` says where the box was given (the flag and
// its value, or the file and line) and the rule gives the allowed range, e.g.
// "--box 10,10,900,20: x+w must be at most the image's width 640". Pure, thread-safe.
cv::Rect ObjectRegion(const cv::Rect& box, double margin, cv::Size image, std::string_view origin);

}  // namespace orbit
