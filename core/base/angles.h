// Azimuth arithmetic (docs/design.md#notation): device azimuths have an unknown offset from
// the model's, so the engines use only differences, wrapped to (-180, 180], and every sector or
// interval is circular so that sequences crossing 0/360 behave like any other.
//
// All functions are pure and thread-safe. Angles are in degrees unless the name says radians.
#pragma once

namespace orbit {

// The angle equivalent to `degrees` in (-180, 180]. REQUIRES: degrees is finite.
double WrapDegrees(double degrees);

// The angle equivalent to `degrees` in [0, 360). REQUIRES: degrees is finite.
double NormaliseAzimuth(double degrees);

// WrapDegrees(to - from): the signed turn from `from` to `to`, positive when `to` lies
// counter-clockwise (toward increasing azimuth) of `from`. Any finite azimuths, however far
// apart (the difference of 1e308 and -1e308 does not overflow). REQUIRES: both finite.
double AzimuthChange(double from, double to);

double DegreesToRadians(double degrees);

// A circular interval of azimuths: from `start` going toward increasing azimuth over `width`
// degrees, i.e. [start, start + width) modulo 360. width is in [0, 360]; width 360 is the
// whole circle.
struct Arc {
  double start = 0;
  double width = 0;
};

// Length in degrees of the intersection of two arcs, counting every turn of the circle once
// (two arcs can meet in two pieces, e.g. [300, 60) and [0, 330)). Result in [0, min(widths)].
// Throws std::invalid_argument when a width is outside [0, 360] or a value is not finite.
double ArcOverlap(const Arc& a, const Arc& b);

}  // namespace orbit
