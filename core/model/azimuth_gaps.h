// AzimuthGaps: the arcs of the circle round an object that a set of views leaves unseen. The
// device reports them for a walk's chosen views (client/capture_views.h) and the server for an
// enrolled object (core/decision/enrollment_feedback.h), so both name the same arcs.
//
// Pure and thread-safe.
#pragma once

#include <vector>

namespace orbit {

struct AzimuthGap {
  double from = 0;  // degrees, [0, 360): the view before the gap
  double to = 0;    // degrees, [0, 360): the view after it (going up, across 360)
  double width() const;
};

// The arcs with no azimuth of `azimuths` (degrees, any finite values) wider than `wider_than`
// degrees, between neighbours in azimuth order and across 360, in azimuth order. Azimuths that
// are equal count once; one azimuth alone leaves the whole circle open: one gap of 360 from it
// to itself. None for no azimuths.
std::vector<AzimuthGap> AzimuthGaps(std::vector<double> azimuths, double wider_than);

}  // namespace orbit
