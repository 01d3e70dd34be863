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
}  // namespace orbit
