// What only the SQLite store does; the contracts it shares with every ModelStore (what goes in
// comes out, ids, names, paging, deletes, reopening) are tested on both stores in
// tests/storage/model_store_test.cc.
#include "storage/sqlite_model_store.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "storage/store_error.h"
#include "tests/support/storage_test_support.h"

namespace orbit {
namespace {

using ::testing::HasSubstr;
using testing::ScratchDir;
using testing::StoreErrorOf;

TEST(SqliteModelStoreTest, OpeningAMissingFileWithoutCreateIsAClearError) {
  ScratchDir dir;
  const auto [code, message] = StoreErrorOf([&] { SqliteModelStore store(dir / "absent.db"); });
  EXPECT_EQ(code, StoreError::Code::kIo);
  EXPECT_THAT(message, HasSubstr("absent.db does not exist"));
  EXPECT_FALSE(std::filesystem::exists(dir / "absent.db"));
}

}  // namespace
}  // namespace orbit
