#include "core/descriptor/cedd_quantisation.h"

#include <cmath>
#include <cstdint>

namespace orbit::cedd {
namespace {

// Quantisation levels of docs/design.md#quantisation, scaled by 1e6 as in the reference.
constexpr double kLevels[4][8] = {
    {180.19686541079636, 23730.024499150866, 61457.152912541605, 113918.55437576842,
     179122.46400035513, 260980.3325940354, 341795.93301552488, 554729.98648386425},
    {209.25176965926232, 22490.5872862417345, 60250.8935141849988, 120705.788057580583,
     181128.08709063051, 234132.081356900555, 325660.617733105708, 520702.175858657472},
    {405.4642173212585, 4877.9763319071481, 10882.170090625908, 18167.239081219657,
     27043.385568785292, 38129.413201299016, 52675.221316293857, 79555.402607004813},
    {968.88475977695578, 10725.159033657819, 24161.205360376698, 41555.917344385321,
     62895.628446402261, 93066.271379694881, 136976.13317822068, 262897.86056221306},
};
// Classes 2 and 3 share a table, and so do classes 4 and 5.
constexpr int kLevelsOfClass[kTextureClasses] = {0, 1, 2, 2, 3, 3};

}  // namespace

DescriptorValues Quantise(const Histogram& histogram) {
  DescriptorValues values{};
  double sum = 0;
  for (double bin : histogram) sum += bin;
  if (sum == 0) return values;
  for (int i = 0; i < kCeddSize; ++i) {
    const double v = histogram[i] / sum;
    const double* levels = kLevels[kLevelsOfClass[i / kColourBins]];
    int best = 0;
    double best_distance = std::fabs(v - levels[0] / 1000000);
    for (int j = 1; j < 8; ++j) {
      const double d = std::fabs(v - levels[j] / 1000000);
      if (d < best_distance) {
        best_distance = d;
        best = j;
      }
    }
    values[i] = static_cast<std::uint8_t>(best);
  }
  return values;
}

}  // namespace orbit::cedd
