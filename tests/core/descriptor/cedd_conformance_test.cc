// CEDD in cedd-lire mode must reproduce the LIRE reference vectors exactly, on the conformance set
// (every branch of the reference: grid modes, sizes, alpha, grey, JPEG, photos) and on all of
// COIL-100.
#include <gtest/gtest.h>

#include <string>

#include "client/image_file.h"
#include "core/descriptor/cedd.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

using testing::DataDir;
using testing::ReadReferenceVectors;

std::string Differences(const DescriptorValues& got, const DescriptorValues& want) {
  std::string text;
  for (int i = 0; i < kCeddSize; ++i) {
    if (got[i] != want[i]) {
      text += " bin " + std::to_string(i) + ": " + std::to_string(got[i]) + " vs " +
              std::to_string(want[i]) + ";";
    }
  }
  return text;
}

// Checks every reference line below `root`; returns how many matched.
int ExpectBitExact(const std::filesystem::path& reference_file, const std::filesystem::path& root,
                   std::size_t expected_lines) {
  const auto references = ReadReferenceVectors(reference_file);
  EXPECT_EQ(references.size(), expected_lines) << reference_file;
  int matched = 0;
  for (const auto& ref : references) {
    const Descriptor d =
        ExtractCedd(ReadImageFile((root / ref.path).string()), DescriptorVariant::kCeddLire);
    EXPECT_EQ(d.variant, DescriptorVariant::kCeddLire);
    if (d.values == ref.values) {
      ++matched;
    } else {
      ADD_FAILURE() << ref.path << " differs from LIRE:" << Differences(d.values, ref.values);
    }
  }
  return matched;
}

TEST(CeddConformance, EveryConformanceImageIsBitExact) {
  const auto dir = DataDir() / "cedd-conformance";
  EXPECT_EQ(ExpectBitExact(dir / "lire-cedd-reference.txt", dir, 66), 66);
}

TEST(CeddConformance, AllOfCoil100IsBitExact) {
  const auto dir = DataDir();
  EXPECT_EQ(ExpectBitExact(dir / "coil-100-lire-cedd.txt", dir, 7200), 7200);
}

}  // namespace
}  // namespace orbit
