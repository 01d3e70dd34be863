#include "core/descriptor/cedd_colour.h"

#include <algorithm>

namespace orbit::cedd {
namespace {

struct Trapezoid {
  double a, b, c, d;
};

// Trapezoid membership exactly as LIRE's FindMembershipValueForTriangles: the three tests are
// applied in turn and the last that holds wins.
double Membership(double x, const Trapezoid& t) {
  double mu = 0;
  if (x >= t.b && x <= t.c) mu = 1;
  if (x >= t.a && x < t.b) mu = (x - t.a) / (t.b - t.a);
  if (x > t.c && x <= t.d) mu = (x - t.c) / (t.c - t.d) + 1;
  return mu;
}

constexpr Trapezoid kHue[8] = {{0, 0, 5, 10},        {5, 10, 35, 50},      {35, 50, 70, 85},
                               {70, 85, 150, 165},   {150, 165, 195, 205}, {195, 205, 265, 280},
                               {265, 280, 315, 330}, {315, 330, 360, 360}};
constexpr Trapezoid kSaturation10[2] = {{0, 0, 10, 75}, {10, 75, 255, 255}};
constexpr Trapezoid kValue10[3] = {{0, 0, 10, 75}, {10, 75, 180, 220}, {180, 220, 255, 255}};
constexpr Trapezoid kSaturation24[2] = {{0, 0, 68, 188}, {68, 188, 255, 255}};
constexpr Trapezoid kValue24[2] = {{0, 0, 68, 188}, {68, 188, 255, 255}};

struct Rule10 {
  int saturation, value, bin;
};
// Per hue, the first group of rules (achromatic outputs: 2 black, 0 white, 1 grey) ...
constexpr Rule10 kAchromaticRules[4] = {{0, 0, 2}, {1, 0, 2}, {0, 2, 0}, {0, 1, 1}};
// ... then, in a second pass over the hues, the two chromatic rules.
constexpr Rule10 kChromaticRules[2] = {{1, 1, -1}, {1, 2, -1}};

int ChromaticBin(int hue) { return hue <= 6 ? 3 + hue : 3; }

// Memberships depend on integer H, S and V only, so they are tabulated once; each entry is
// computed by the same expression as the reference, hence bit-identical.
struct MembershipTables {
  std::array<std::array<double, 8>, 360> hue;
  // Per hue, the sets it belongs to (membership > 0), in increasing order: at most two, since
  // only neighbouring trapezoids overlap. The rules of any other set never fire.
  struct HueSets {
    std::array<int, 8> sets;
    int count = 0;
  };
  std::array<HueSets, 360> hue_sets;
  std::array<std::array<double, 2>, 256> saturation10;
  std::array<std::array<double, 3>, 256> value10;
  std::array<std::array<double, 2>, 256> saturation24;
  std::array<std::array<double, 2>, 256> value24;

  MembershipTables() {
    for (int h = 0; h < 360; ++h) {
      for (int i = 0; i < 8; ++i) {
        hue[h][i] = Membership(h, kHue[i]);
        if (hue[h][i] > 0) hue_sets[h].sets[hue_sets[h].count++] = i;
      }
    }
    for (int x = 0; x < 256; ++x) {
      for (int i = 0; i < 2; ++i) saturation10[x][i] = Membership(x, kSaturation10[i]);
      for (int i = 0; i < 3; ++i) value10[x][i] = Membership(x, kValue10[i]);
      for (int i = 0; i < 2; ++i) saturation24[x][i] = Membership(x, kSaturation24[i]);
      for (int i = 0; i < 2; ++i) value24[x][i] = Membership(x, kValue24[i]);
    }
  }
};

const MembershipTables& Tables() {
  static const MembershipTables tables;
  return tables;
}

}  // namespace

Hsv RgbToHsv(int red, int green, int blue) {
  const double max = std::max(red, std::max(green, blue));
  const double min = std::min(red, std::min(green, blue));
  Hsv hsv;
  hsv.v = static_cast<int>(max);
  if (max != 0) hsv.s = static_cast<int>(255 - 255 * (min / max));
  if (max != min) {
    const int imax = static_cast<int>(max);
    if (imax == red && green >= blue) {
      hsv.h = static_cast<int>(60 * (green - blue) / (max - min));
    } else if (imax == red) {
      hsv.h = static_cast<int>(359 + 60 * (green - blue) / (max - min));
    } else if (imax == green) {
      hsv.h = static_cast<int>(119 + 60 * (blue - red) / (max - min));
    } else {
      hsv.h = static_cast<int>(239 + 60 * (red - green) / (max - min));
    }
  }
  return hsv;
}

Fuzzy10 FuzzyLink10(const Hsv& hsv) {
  const MembershipTables& t = Tables();
  const auto& hue = t.hue[hsv.h];
  const auto& sat = t.saturation10[hsv.s];
  const auto& val = t.value10[hsv.v];
  const auto& hue_sets = t.hue_sets[hsv.h];
  // Rules fire in the reference's order (48 rules: 4 per hue, then 2 per hue), so each bin's
  // sum is accumulated in the same order; a rule fires only if all three memberships are > 0.
  Fuzzy10 bins{};
  for (int i = 0; i < hue_sets.count; ++i) {
    const int h = hue_sets.sets[i];
    for (const Rule10& rule : kAchromaticRules) {
      if (sat[rule.saturation] > 0 && val[rule.value] > 0) {
        bins[rule.bin] += std::min(hue[h], std::min(sat[rule.saturation], val[rule.value]));
      }
    }
  }
  for (int i = 0; i < hue_sets.count; ++i) {
    const int h = hue_sets.sets[i];
    for (const Rule10& rule : kChromaticRules) {
      if (sat[rule.saturation] > 0 && val[rule.value] > 0) {
        bins[ChromaticBin(h)] += std::min(hue[h], std::min(sat[rule.saturation], val[rule.value]));
      }
    }
  }
  return bins;
}

Fuzzy24 FuzzyLink24(const Hsv& hsv, const Fuzzy10& fuzzy10) {
  const MembershipTables& t = Tables();
  const auto& sat = t.saturation24[hsv.s];
  const auto& val = t.value24[hsv.v];
  double chromatic = 0;
  for (int i = 3; i < 10; ++i) chromatic += fuzzy10[i];

  // Light (0), normal (1), dark (2) shares; rules (S,V -> k): (1,1->1) (0,0->2) (0,1->0) (1,0->2).
  std::array<double, 3> shade{};
  if (chromatic > 0) {
    struct Rule24 {
      int saturation, value, shade;
    };
    static constexpr Rule24 kRules[4] = {{1, 1, 1}, {0, 0, 2}, {0, 1, 0}, {1, 0, 2}};
    for (const Rule24& rule : kRules) {
      if (sat[rule.saturation] > 0 && val[rule.value] > 0) {
        shade[rule.shade] += std::min(sat[rule.saturation], val[rule.value]);
      }
    }
  }

  Fuzzy24 bins{};
  for (int i = 0; i < 3; ++i) bins[i] = fuzzy10[i];
  for (int i = 3; i < 10; ++i) {
    for (int k = 0; k < 3; ++k) bins[(i - 2) * 3 + k] = fuzzy10[i] * shade[k];
  }
  return bins;
}

Fuzzy24 FuzzyColour(int red, int green, int blue) {
  const Hsv hsv = RgbToHsv(red, green, blue);
  return FuzzyLink24(hsv, FuzzyLink10(hsv));
}

}  // namespace orbit::cedd
