// From an HMM's state similarities to what its decoding reads (docs/design.md#orientation-hmm):
// emissions, their bounds in exact integer units, and sharpening. Shared by the HMM that scores
// every object and the one that scores candidates (core/engines/candidate_hmm.h), so that both
// give an object the same emissions to the last bit.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "core/base/cpu_dispatch.h"

namespace orbit {

// b_i is floored at this share of the object's sum over its states, so that a zero similarity
// never makes every path impossible.
inline constexpr double kEmissionFloor = 1e-12;

// An unseen object's emissions as a window keeps them (below): the emission is |-1| = 1 in
// every state (b uniform) and its similarity on any path max(-1, 0) = 0, so that decoding reads
// both from the kept values alone.
inline constexpr float kUnseenEmission = -1.0f;

// In place, values[i * n + o] = TC(S_i, o_t) becomes b_i(o_t) up to a per-frame constant:
// the similarity floored at 1e-12 of the object's sum over its states (> 0), or
// kUnseenEmission for every state when that sum is 0 (the object is unseen in the frame).
// best[o] is the object's highest emission, or 0 when it is unseen (its similarity on any
// path), so best[o] > 0 exactly when the object is seen. `sum` is scratch of n floats. Called
// with n = 1 on one object's values, it gives what it gives that object among many.
ORBIT_HOT_LOOP void EmissionsFromSimilarities(float* __restrict values, int states,
                                              float* __restrict sum, float* __restrict best,
                                              std::size_t n) {
  for (std::size_t o = 0; o < n; ++o) sum[o] = 0.0f;
  for (int i = 0; i < states; ++i) {
    const float* row = &values[static_cast<std::size_t>(i) * n];
    for (std::size_t o = 0; o < n; ++o) sum[o] += row[o];
  }
  for (std::size_t o = 0; o < n; ++o) best[o] = 0.0f;
  for (int i = 0; i < states; ++i) {
    float* row = &values[static_cast<std::size_t>(i) * n];
    for (std::size_t o = 0; o < n; ++o) {
      const float floor = static_cast<float>(kEmissionFloor) * sum[o];
      row[o] = sum[o] > 0.0f ? std::max(row[o], floor) : kUnseenEmission;
      best[o] = sum[o] > 0.0f ? std::max(best[o], row[o]) : 0.0f;
    }
  }
}

// An object's best emission in a frame, as the window keeps it for the bounds (Assess): in units
// of 2^-15, rounded up, so that a sum of them is never below the sum of the emissions, and exact
// in integers. 16 bits hold up to 2: a Tanimoto coefficient in float is at most 1 and a few ulps.
inline constexpr float kBoundUnitsPerOne = 32768.0f;

// units[o] = ceil(best[o] * 2^15): exact, as scaling by a power of two is.
ORBIT_HOT_LOOP void BoundUnits(const float* __restrict best, std::uint16_t* __restrict units,
                               std::size_t n) {
  for (std::size_t o = 0; o < n; ++o) {
    units[o] = static_cast<std::uint16_t>(std::ceil(best[o] * kBoundUnitsPerOne));
  }
}

// bound[o] += units[o], or -= with `subtract`: a window's bounds follow its frames in
// integers, exactly, as frames enter and leave.
ORBIT_HOT_LOOP void AddBounds(const std::uint16_t* __restrict units, bool subtract,
                              std::uint32_t* __restrict bound, std::size_t n) {
  if (subtract) {
    for (std::size_t o = 0; o < n; ++o) bound[o] -= units[o];
  } else {
    for (std::size_t o = 0; o < n; ++o) bound[o] += units[o];
  }
}

// In place, values[k] = values[k]^(2^squarings) (EngineOptions::hmm_sharpness). At the 32nd
// power a similarity under about 0.065 underflows to 0: an object that matches a frame that
// poorly in every state gets an arbitrary path through it and reads 0 there, which changes
// nothing for the objects that can rank.
// Values that would fall below FLT_MIN are set to 0 at once: subnormal floats cost the
// multiplications here and in BatchViterbi tens of cycles each.
ORBIT_HOT_LOOP void Sharpen(float* __restrict values, std::size_t count, int squarings) {
  if (squarings == 0) return;
  // The smallest value whose 2^squarings-th power is a normal float.
  const float smallest =
      std::pow(std::numeric_limits<float>::min(), 1.0f / static_cast<float>(1 << squarings));
  for (std::size_t k = 0; k < count; ++k) {
    float v = values[k] < smallest ? 0.0f : values[k];
    for (int s = 0; s < squarings; ++s) v *= v;
    values[k] = v;
  }
}

}  // namespace orbit
