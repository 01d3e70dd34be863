// The descriptor's vocabulary (core/descriptor/descriptor.h): variant names and the one check of
// values that arrive from outside.
#include "core/descriptor/descriptor.h"

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/test_data.h"

namespace orbit {
namespace {

using orbit::testing::ErrorMessageOf;
TEST(DescriptorTest, VariantNamesRoundTrip) {
  for (DescriptorVariant variant : kDescriptorVariants) {
    EXPECT_EQ(ParseVariant(VariantName(variant)), variant);
  }
  EXPECT_EQ(VariantName(DescriptorVariant::kCeddLire), "cedd-lire");
  EXPECT_EQ(VariantName(DescriptorVariant::kCeddFull), "cedd-full");
  EXPECT_EQ(VariantName(DescriptorVariant::kCeddRobust), "cedd-robust");
  EXPECT_EQ(VariantName(DescriptorVariant::kCeddHsvHog), "cedd-hsv-hog");
  EXPECT_EQ(VariantName(DescriptorVariant::kCeddHsvLayout), "cedd-hsv-layout");
  EXPECT_EQ(VariantName(DescriptorVariant::kCeddSoftHsvHog), "cedd-soft-hsv-hog");
  EXPECT_EQ(VariantNames(),
            (std::vector<std::string>{"cedd-lire", "cedd-full", "cedd-robust", "cedd-hsv-hog",
                                      "cedd-hsv-layout", "cedd-soft-hsv-hog"}));
  EXPECT_EQ(DescriptorLength(DescriptorVariant::kCeddRobust), 144);
  EXPECT_EQ(DescriptorLength(DescriptorVariant::kCeddHsvHog), 480);
  EXPECT_EQ(DescriptorLength(DescriptorVariant::kCeddHsvLayout), 480);
  EXPECT_EQ(DescriptorLength(DescriptorVariant::kCeddSoftHsvHog), 480);
  EXPECT_EQ(ParseVariant("CEDD-LIRE"), std::nullopt);
  EXPECT_EQ(ParseVariant(""), std::nullopt);
}

TEST(DescriptorTest, ValidateDescriptorValuesNamesTheFirstValueAbove7) {
  std::vector<std::uint8_t> values(kDescriptorSize, 7);
  EXPECT_NO_THROW(ValidateDescriptorValues(values));
  values[17] = 9;
  values[40] = 200;
  EXPECT_EQ(ErrorMessageOf([&] { ValidateDescriptorValues(values, "frame.cedd"); }),
            "frame.cedd value 9 at index 17 is outside 0..7");
  values[17] = 8;
  EXPECT_EQ(ErrorMessageOf([&] { ValidateDescriptorValues(values); }),
            "descriptor value 8 at index 17 is outside 0..7");
}

TEST(DescriptorTest, DescriptorFromBytesNeedsExactlyTheVariantsLengthInRange) {
  constexpr auto kFull = DescriptorVariant::kCeddFull;
  std::vector<std::uint8_t> bytes(kCeddSize, 7);
  bytes[5] = 3;
  const DescriptorValues values = DescriptorFromBytes(bytes, kFull);
  EXPECT_EQ(values[5], 3);
  EXPECT_EQ(values[143], 7);
  EXPECT_EQ(values[144], 0) << "values past a CEDD variant's length are 0";
  bytes.pop_back();
  EXPECT_EQ(ErrorMessageOf([&] { DescriptorFromBytes(bytes, kFull); }),
            "descriptor has 143 values, expected 144");
  bytes.push_back(7);
  bytes.push_back(7);
  EXPECT_EQ(ErrorMessageOf([&] { DescriptorFromBytes(bytes, kFull, "view.cedd"); }),
            "view.cedd has 145 values, expected 144");
  bytes.pop_back();
  bytes[0] = 8;
  EXPECT_EQ(ErrorMessageOf([&] { DescriptorFromBytes(bytes, kFull); }),
            "descriptor value 8 at index 0 is outside 0..7");
  bytes[0] = 7;
  EXPECT_EQ(ErrorMessageOf([&] { DescriptorFromBytes(bytes, DescriptorVariant::kCeddHsvHog); }),
            "descriptor has 144 values, expected 480");
  bytes.resize(kDescriptorSize, 2);
  EXPECT_EQ(DescriptorFromBytes(bytes, DescriptorVariant::kCeddHsvHog)[479], 2);
  EXPECT_EQ(DescriptorBytes(values, kFull).size(), 144u);
  EXPECT_EQ(DescriptorBytes(values, DescriptorVariant::kCeddHsvHog).size(), 480u);
}

}  // namespace
}  // namespace orbit
