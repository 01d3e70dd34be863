// The change log's kind names: written once, read back to the same kind.
#include "storage/model_change.h"

#include <gtest/gtest.h>

namespace orbit {
namespace {

TEST(ModelChangeTest, KindNamesAreTheLogsAndParseBack) {
  EXPECT_EQ(ModelChangeKindName(ModelChangeKind::kEnroll), "enroll");
  EXPECT_EQ(ModelChangeKindName(ModelChangeKind::kAddViews), "add_views");
  EXPECT_EQ(ModelChangeKindName(ModelChangeKind::kDelete), "delete");
  EXPECT_EQ(ModelChangeKindName(ModelChangeKind::kRename), "rename");
  for (ModelChangeKind kind : {ModelChangeKind::kEnroll, ModelChangeKind::kAddViews,
                               ModelChangeKind::kDelete, ModelChangeKind::kRename}) {
    EXPECT_EQ(ParseModelChangeKind(ModelChangeKindName(kind)), kind);
  }
  EXPECT_EQ(ParseModelChangeKind("Enroll"), std::nullopt);
  EXPECT_EQ(ParseModelChangeKind(""), std::nullopt);
}

}  // namespace
TEST(ModelChangeTest, CommittedTimeReadsTheLogsUtcTimestamp) {
  ModelChange change{.committed_at = "2026-11-24T21:04:53.149Z"};
  const auto time = CommittedTime(change);
  ASSERT_TRUE(time.has_value());
  // 1795554293 s: date -u -d 2026-11-24T21:04:53Z +%s
  EXPECT_EQ(std::chrono::duration_cast<std::chrono::milliseconds>(time->time_since_epoch()).count(),
            1795554293149);
  for (const char* bad : {"", "2026-11-24 21:04:53.149Z", "2026-11-24T21:04:53.149",
                          "2026-11-24T21:04:53.149Zx", "yesterday"}) {
    change.committed_at = bad;
    EXPECT_EQ(CommittedTime(change), std::nullopt) << bad;
  }
}

}  // namespace orbit
