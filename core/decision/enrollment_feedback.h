// What an enrollment got, for the operator who walks round the object: where the
// views leave the object unseen, which views repeat others, and which objects already enrolled
// it could be taken for. Like the scanning apps that guide a user round an object, but after
// the fact, in the Enroll and AddViews replies.
//
//   gaps:        azimuth arcs wider than kCoverageGapDegrees with no view (circularly;
//                core/model/azimuth_gaps.h)
//   redundant:   views whose TC with a view before them (azimuth order) is at least
//                kRedundantSimilarity: the camera did not move, or the object looks the same
//                from there (a can turning on its axis); they add no information
//   confusable:  the kConfusableObjects other objects of the index with the highest
//                similarity: the mean over this object's views of their best TC with that
//                object's views; and how many of this object's views that object holds a view
//                closer to than this object's own other views (a frame taken there could go
//                to it)
//
// Pure and thread-safe.
#pragma once

#include <vector>

#include "core/index/view_index.h"
#include "core/model/azimuth_gaps.h"
#include "core/model/object_model.h"

namespace orbit {

inline constexpr double kCoverageGapDegrees = 30;
// Above what most of COIL-100's neighbouring views, 5 degrees apart, reach in cedd-robust:
// 0.995 and above is a repeat.
inline constexpr double kRedundantSimilarity = 0.995;
inline constexpr int kConfusableObjects = 3;
// In an index of more than kScanEveryObjectUpTo objects, the confusable objects are looked for
// among candidates instead of in every object: the kConfusableCandidatesPerProbe objects whose
// summaries are most like each of kConfusableProbes views spread round the object
// (ViewIndexSnapshot::ObjectCandidates), each then scored exactly as above. Scanning every view
// for each of an object's views costs an enrollment time in proportion to the catalogue (seconds
// at ten thousand objects of 72 views); an object no probe proposes is taken to be less
// confusable than those that are (docs/design.md#enrollment-feedback).
inline constexpr int kConfusableProbes = 8;
inline constexpr int kConfusableCandidatesPerProbe = 32;

struct Confusion {
  ObjectId object = 0;
  double similarity = 0;  // mean over this object's views of the best TC with that object's
  int closer_views = 0;   // views of this object to which that object holds a closer view
};

struct EnrollmentFeedback {
  std::vector<AzimuthGap> gaps;            // in azimuth order
  std::vector<double> redundant_azimuths;  // azimuths of the redundant views, ascending
  std::vector<Confusion> confusable;       // most similar first
};

// The feedback on `object` against the other objects of `index` (the object itself, when the
// index holds it, is left out by id). Throws std::invalid_argument when `object` has no views.
EnrollmentFeedback AssessEnrollment(const ObjectModel& object, const ViewIndexSnapshot& index);

}  // namespace orbit
