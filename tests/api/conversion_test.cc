// The conversions both ends of a call share (api/conversion.h), with hand-built values.
#include "api/conversion.h"

#include <stdexcept>

#include <gtest/gtest.h>

namespace orbit {
namespace {

TEST(ConversionTest, VariantsRoundTripAndUnknownOnesAreRefusedByName) {
  for (const DescriptorVariant variant : kDescriptorVariants) {
    EXPECT_EQ(FromProtoVariant(ToProtoVariant(variant)), variant);
  }
  EXPECT_EQ(ToProtoVariant(DescriptorVariant::kCeddLire), v1::CEDD_LIRE);
  EXPECT_EQ(ToProtoVariant(DescriptorVariant::kCeddFull), v1::CEDD_FULL);
  EXPECT_EQ(ProtoVariantName(v1::CEDD_FULL), "cedd-full");
  EXPECT_EQ(ToProtoVariant(DescriptorVariant::kCeddRobust), v1::CEDD_ROBUST);
  EXPECT_EQ(ProtoVariantName(v1::CEDD_ROBUST), "cedd-robust");
  EXPECT_EQ(ProtoVariantName(v1::DESCRIPTOR_VARIANT_UNSPECIFIED), "unspecified");
  EXPECT_EQ(ProtoVariantName(static_cast<v1::DescriptorVariant>(9)), "unknown (9)");
  // Neither end guesses a variant: both refuse what they do not know.
  for (const auto bad :
       {v1::DESCRIPTOR_VARIANT_UNSPECIFIED, static_cast<v1::DescriptorVariant>(9)}) {
    try {
      FromProtoVariant(bad);
      ADD_FAILURE() << "accepted " << bad;
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()), "descriptor variant is " + ProtoVariantName(bad));
    }
  }
}

TEST(ConversionTest, DescriptorFromWireNamesTheField) {
  constexpr auto kFull = DescriptorVariant::kCeddFull;
  std::string bytes(kCeddSize, '\x07');
  bytes[3] = '\x02';
  EXPECT_EQ(DescriptorFromWire(bytes, "", kFull, "frame")[3], 2);
  bytes[17] = '\x09';
  try {
    DescriptorFromWire(bytes, "", kFull, "frame");
    ADD_FAILURE() << "accepted a 9";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "frame.cedd value 9 at index 17 is outside 0..7");
  }
  try {
    DescriptorFromWire(std::string(10, '\0'), "", kFull, "view");
    ADD_FAILURE() << "accepted 10 bytes";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "view.cedd has 10 values, expected 144");
  }
}

TEST(ConversionTest, AppearanceChannelsTravelBesideTheCedd) {
  constexpr auto kHsvHog = DescriptorVariant::kCeddHsvHog;
  const std::string cedd(kCeddSize, '\x01');
  std::string appearance(kDescriptorSize - kCeddSize, '\x03');
  appearance[0] = '\x05';
  const DescriptorValues values = DescriptorFromWire(cedd, appearance, kHsvHog, "frame");
  EXPECT_EQ(values[kCeddSize - 1], 1);
  EXPECT_EQ(values[kCeddSize], 5);
  EXPECT_EQ(values[kDescriptorSize - 1], 3);
  std::string cedd_back, appearance_back;
  SetWireDescriptor(values, kHsvHog, &cedd_back, &appearance_back);
  EXPECT_EQ(cedd_back, cedd);
  EXPECT_EQ(appearance_back, appearance);
  try {
    DescriptorFromWire(cedd, "", kHsvHog, "frame");
    ADD_FAILURE() << "accepted a frame without its appearance channels";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "frame.appearance has 0 values, expected 336 for cedd-hsv-hog");
  }
  try {
    DescriptorFromWire(cedd, appearance, DescriptorVariant::kCeddRobust, "frame");
    ADD_FAILURE() << "accepted appearance channels in a CEDD variant";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "frame.appearance has 336 values, expected 0 for cedd-robust");
  }
  appearance[7] = '\x08';
  try {
    DescriptorFromWire(cedd, appearance, kHsvHog, "view");
    ADD_FAILURE() << "accepted an 8";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "view.appearance value 8 at index 7 is outside 0..7");
  }
}

TEST(ConversionTest, ViewCarriesEveryStoredField) {
  ModelView view;
  view.descriptor[0] = 7;
  view.descriptor[143] = 1;
  view.azimuth = 35;
  view.typical_distance = 0.25;
  v1::View wire = ToProtoView(view, DescriptorVariant::kCeddFull);
  ASSERT_EQ(wire.cedd().size(), 144u);
  EXPECT_TRUE(wire.appearance().empty());
  EXPECT_EQ(wire.cedd()[0], '\x07');
  EXPECT_EQ(wire.cedd()[143], '\x01');
  EXPECT_EQ(wire.azimuth_deg(), 35);
  EXPECT_FALSE(wire.has_elevation_deg());
  EXPECT_EQ(wire.typical_distance(), 0.25);
  EXPECT_TRUE(wire.thumbnail().empty());
  EXPECT_EQ(
      DescriptorFromWire(wire.cedd(), wire.appearance(), DescriptorVariant::kCeddFull, "view"),
      view.descriptor);

  view.elevation = -12.5;
  wire = ToProtoView(view, DescriptorVariant::kCeddFull, "png bytes");
  EXPECT_EQ(wire.elevation_deg(), -12.5);
  EXPECT_EQ(wire.thumbnail(), "png bytes");

  view.descriptor[kDescriptorSize - 1] = 6;
  wire = ToProtoView(view, DescriptorVariant::kCeddHsvHog);
  EXPECT_EQ(wire.cedd().size(), 144u);
  ASSERT_EQ(wire.appearance().size(), 336u);
  EXPECT_EQ(wire.appearance()[335], '\x06');
}

}  // namespace
}  // namespace orbit
