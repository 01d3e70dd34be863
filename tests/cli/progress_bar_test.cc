#include "cli/progress_bar.h"

#include <algorithm>
#include <chrono>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace orbit {
namespace {

using ::testing::HasSubstr;

TEST(ProgressBarTest, RendersFractionCountAndTimeLeft) {
  EXPECT_EQ(ProgressBar::Render("trials", 15, 60, 95),
            "trials [=======>                      ]  25% 15/60, 1m35s left");
  EXPECT_EQ(ProgressBar::Render("trials", 60, 60, 0),
            "trials [==============================] 100% 60/60");
  EXPECT_EQ(ProgressBar::Render("descriptors", 0, 10, -1),
            "descriptors [                              ]   0% 0/10");
  EXPECT_THAT(ProgressBar::Render("trials", 1, 1000, 7300), HasSubstr("2h01m left"));
}

TEST(ProgressBarTest, StaysQuietForShortRuns) {
  std::ostringstream out;
  {
    ProgressBar bar(out, /*terminal=*/false, std::chrono::milliseconds(60000));
    for (int i = 1; i <= 10; ++i) bar.Update("trials", i, 10);
  }
  EXPECT_EQ(out.str(), "");
}

TEST(ProgressBarTest, WritesOneLinePerTenthOffTerminal) {
  std::ostringstream out;
  {
    ProgressBar bar(out, /*terminal=*/false, std::chrono::milliseconds(0));
    for (int i = 1; i <= 100; ++i) bar.Update("trials", i, 100);
  }
  const std::string text = out.str();
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 11);  // 0%, 10%, ..., 100%
  EXPECT_THAT(text, HasSubstr("trials [==============================] 100% 100/100\n"));
  EXPECT_EQ(text.find('\r'), std::string::npos);
}

}  // namespace
}  // namespace orbit
