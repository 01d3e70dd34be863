// Similarity between CEDD descriptors (docs/design.md#similarity).
//
// All functions are pure and thread-safe.
#pragma once

#include "core/descriptor/descriptor.h"

namespace orbit {

// Tanimoto coefficient on the raw 0..7 values: TC(q,c) = q.c / (q.q + c.c - q.c).
// Two all-zero vectors give 1; exactly one all-zero vector gives 0. Result in [0, 1].
double Tanimoto(const DescriptorValues& q, const DescriptorValues& c);

// T = 1 - TC, the distance the engines minimise.
double TanimotoDistance(const DescriptorValues& q, const DescriptorValues& c);

// Rolls the four directional texture classes by `steps` x 45 degrees: each step moves the
// 24-bin block of class 2 (horizontal) to class 4 (45), 4 to 3 (vertical), 3 to 5 (135) and
// 5 to 2. Classes 0 and 1 stay. steps is taken modulo 4 (negative steps roll backwards).
DescriptorValues RollOrientation(const DescriptorValues& values, int steps);

// TC_R(q,c) = max over roll in {0,45,90,135} of TC(roll(q), c): tolerant to camera roll.
double TanimotoRotationTolerant(const DescriptorValues& q, const DescriptorValues& c);

// LIRE's CEDD distance, in [0, 100]: 100 * (1 - TC(a/sum(a), b/sum(b))); 0 when both sums are
// 0, 100 when exactly one is. Evaluated in LIRE's order so that it matches LIRE to 1e-9.
double LireDistance(const DescriptorValues& a, const DescriptorValues& b);

}  // namespace orbit
