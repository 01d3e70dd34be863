#include "core/base/angles.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <gtest/gtest.h>

namespace orbit {
namespace {

TEST(AnglesTest, WrapDegreesLandsInMinus180To180) {
  EXPECT_EQ(WrapDegrees(0), 0);
  EXPECT_EQ(WrapDegrees(190), -170);
  EXPECT_EQ(WrapDegrees(-190), 170);
  EXPECT_EQ(WrapDegrees(180), 180);  // the interval is (-180, 180]
  EXPECT_EQ(WrapDegrees(-180), 180);
  EXPECT_EQ(WrapDegrees(540), 180);
  EXPECT_EQ(WrapDegrees(359), -1);
  EXPECT_EQ(WrapDegrees(-725), -5);
}

TEST(AnglesTest, NormaliseAzimuthLandsIn0To360) {
  EXPECT_EQ(NormaliseAzimuth(360), 0);
  EXPECT_EQ(NormaliseAzimuth(-5), 355);
  EXPECT_EQ(NormaliseAzimuth(725), 5);
  EXPECT_EQ(NormaliseAzimuth(-1e-20), 0);  // would round to 360
  EXPECT_FALSE(std::signbit(NormaliseAzimuth(-0.0)));
}

TEST(AnglesTest, AzimuthChangeIsTheShortSignedTurnAcrossZero) {
  EXPECT_EQ(AzimuthChange(350, 10), 20);
  EXPECT_EQ(AzimuthChange(10, 350), -20);
  EXPECT_EQ(AzimuthChange(100, 100), 0);
  EXPECT_DOUBLE_EQ(DegreesToRadians(180), std::numbers::pi);
}

TEST(AnglesTest, AzimuthChangeOfFarApartFiniteAzimuthsDoesNotOverflow) {
  // 1e308 = 296 (mod 360) and -1e308 = 64 (mod 360), by hand with an exact fmod: the turn from
  // -1e308 to 1e308 is 296 - 64 = 232, i.e. -128.
  EXPECT_EQ(NormaliseAzimuth(1e308), 296.0);
  EXPECT_EQ(NormaliseAzimuth(-1e308), 64.0);
  EXPECT_EQ(AzimuthChange(-1e308, 1e308), -128.0);
  EXPECT_EQ(AzimuthChange(1e308, -1e308), 128.0);
  EXPECT_EQ(AzimuthChange(-1e308, -1e308), 0.0);
}

TEST(AnglesTest, ArcOverlapCountsBothPiecesAcrossZero) {
  // [350, 20) and [0, 30): [0, 20).
  EXPECT_DOUBLE_EQ(ArcOverlap({350, 30}, {0, 30}), 20);
  // [300, 60) and [0, 330): [300, 330) and [0, 60).
  EXPECT_DOUBLE_EQ(ArcOverlap({300, 120}, {0, 330}), 90);
  EXPECT_DOUBLE_EQ(ArcOverlap({0, 330}, {300, 120}), 90);
  // Disjoint, touching, contained, whole circle, starts given outside [0, 360).
  EXPECT_DOUBLE_EQ(ArcOverlap({0, 90}, {180, 90}), 0);
  EXPECT_DOUBLE_EQ(ArcOverlap({0, 90}, {90, 90}), 0);
  EXPECT_DOUBLE_EQ(ArcOverlap({10, 100}, {40, 20}), 20);
  EXPECT_DOUBLE_EQ(ArcOverlap({0, 360}, {123, 45}), 45);
  EXPECT_DOUBLE_EQ(ArcOverlap({0, 360}, {0, 360}), 360);
  EXPECT_DOUBLE_EQ(ArcOverlap({-30, 60}, {690, 60}), 60);  // both are [330, 30)
}

TEST(AnglesTest, ArcOverlapRejectsBadWidths) {
  EXPECT_THROW(ArcOverlap({0, -1}, {0, 10}), std::invalid_argument);
  EXPECT_THROW(ArcOverlap({0, 10}, {0, 361}), std::invalid_argument);
  EXPECT_THROW(ArcOverlap({NAN, 10}, {0, 10}), std::invalid_argument);
}

}  // namespace
}  // namespace orbit
