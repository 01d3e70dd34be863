#include "core/descriptor/similarity.h"

#include <algorithm>

namespace orbit {

double Tanimoto(const DescriptorValues& q, const DescriptorValues& c) {
  // Integer dot products are exact; only the final ratio is rounded.
  int qc = 0, qq = 0, cc = 0;
  for (int i = 0; i < kDescriptorSize; ++i) {
    qc += q[i] * c[i];
    qq += q[i] * q[i];
    cc += c[i] * c[i];
  }
  if (qq == 0 && cc == 0) return 1.0;
  const int denominator = qq + cc - qc;  // > 0 unless both are zero (Cauchy-Schwarz)
  return static_cast<double>(qc) / denominator;
}

double TanimotoDistance(const DescriptorValues& q, const DescriptorValues& c) {
  return 1.0 - Tanimoto(q, c);
}

DescriptorValues RollOrientation(const DescriptorValues& values, int steps) {
  // One 45-degree step: class 2 -> 4 -> 3 -> 5 -> 2 (horizontal -> 45 -> vertical -> 135).
  static constexpr int kNext[kTextureClasses] = {0, 1, 4, 5, 3, 2};
  steps = ((steps % 4) + 4) % 4;
  DescriptorValues rolled = values;
  for (int s = 0; s < steps; ++s) {
    DescriptorValues next{};
    for (int cls = 0; cls < kTextureClasses; ++cls) {
      std::copy_n(rolled.begin() + cls * kColourBins, kColourBins,
                  next.begin() + kNext[cls] * kColourBins);
    }
    rolled = next;
  }
  return rolled;
}

double TanimotoRotationTolerant(const DescriptorValues& q, const DescriptorValues& c) {
  double best = Tanimoto(q, c);
  for (int steps = 1; steps < 4; ++steps) {
    best = std::max(best, Tanimoto(RollOrientation(q, steps), c));
  }
  return best;
}

double LireDistance(const DescriptorValues& a, const DescriptorValues& b) {
  double sum_a = 0, sum_b = 0;
  for (int i = 0; i < kCeddSize; ++i) {
    sum_a += a[i];
    sum_b += b[i];
  }
  if (sum_a == 0 && sum_b == 0) return 0.0;
  if (sum_a == 0 || sum_b == 0) return 100.0;
  double ab = 0, bb = 0, aa = 0;
  for (int i = 0; i < kCeddSize; ++i) {
    const double na = a[i] / sum_a;
    const double nb = b[i] / sum_b;
    ab += na * nb;
    bb += nb * nb;
    aa += na * na;
  }
  return 100.0 - 100.0 * (ab / (bb + aa - ab));
}

}  // namespace orbit
