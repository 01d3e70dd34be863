// ModelCatalogue (server/model_catalogue.h) on a real SQLite store: every change reaches the
// index as one snapshot, and an object another store user deleted is NOT_FOUND, never a crash.
#include "server/model_catalogue.h"

#include <atomic>
#include <thread>

#include <gtest/gtest.h>

#include "storage/sqlite_model_store.h"
#include "storage/store_error.h"
#include "tests/support/storage_test_support.h"

namespace orbit::server {
namespace {

using orbit::testing::ScratchDir;
using orbit::testing::SyntheticObject;
using orbit::testing::SyntheticView;

SqliteModelStoreOptions Create() {
  SqliteModelStoreOptions options;
  options.create_if_missing = true;
  return options;
}

StoreError::Code CodeOf(const std::function<void()>& call) {
  try {
    call();
  } catch (const StoreError& e) {
    return e.code();
  }
  ADD_FAILURE() << "no StoreError";
  return StoreError::Code::kIo;
}

TEST(ModelCatalogueTest, EnrollAddViewsAndDeleteReachTheIndex) {
  ScratchDir dir;
  SqliteModelStore store(dir / "models.db", Create());
  ModelCatalogue catalogue(store, DescriptorVariant::kCeddLire, {});
  catalogue.Load();
  const ObjectSummary mug = catalogue.Enroll(SyntheticObject("mug", 4));
  EXPECT_EQ(mug.view_count, 4);
  ASSERT_NE(catalogue.Snapshot()->Find(mug.id), nullptr);

  const ObjectSummary grown = catalogue.AddViews(mug.id, {SyntheticView(50, 200)}, {});
  EXPECT_EQ(grown.view_count, 5);
  EXPECT_EQ(catalogue.Snapshot()->Find(mug.id)->model().views.size(), 5u);
  EXPECT_EQ(catalogue.Snapshot()->object_count(), 1u);

  EXPECT_EQ(CodeOf([&] { catalogue.AddViews(mug.id + 1, {SyntheticView(51, 0)}, {}); }),
            StoreError::Code::kNotFound);
  EXPECT_EQ(catalogue.Delete(mug.id).name, "mug");
  EXPECT_EQ(catalogue.Snapshot()->object_count(), 0u);
  EXPECT_EQ(CodeOf([&] { catalogue.Delete(mug.id); }), StoreError::Code::kNotFound);

  Enrollment full = SyntheticObject("bowl", 2);
  full.variant = DescriptorVariant::kCeddFull;
  EXPECT_THROW(catalogue.Enroll(full), std::invalid_argument);
  EXPECT_EQ(store.Find("bowl"), std::nullopt);
}

TEST(ModelCatalogueTest, FramesDuringAddViewsNeverSeeTheObjectMissing) {
  // A session takes the current snapshot for each frame. While views are added to "mug" again
  // and again, every snapshot must hold it (before: the old version; after: the new one).
  ScratchDir dir;
  SqliteModelStore store(dir / "models.db", Create());
  ModelCatalogue catalogue(store, DescriptorVariant::kCeddLire, {.search = SearchMode::kKdTree});
  catalogue.Load();
  const ObjectId mug = catalogue.Enroll(SyntheticObject("mug", 8)).id;
  catalogue.Enroll(SyntheticObject("bowl", 8, 100));

  std::atomic<bool> done{false};
  std::atomic<int> frames{0}, missing{0};
  std::thread session([&] {
    while (!done.load()) {
      const auto snapshot = catalogue.Snapshot();
      if (snapshot->Find(mug) == nullptr) ++missing;
      // A frame equal to one of mug's views finds mug first.
      if (snapshot->Search(SyntheticView(1, 0).descriptor, 1).at(0).object != mug) ++missing;
      ++frames;
    }
  });
  for (int i = 0; i < 40; ++i) catalogue.AddViews(mug, {SyntheticView(1000 + i, i)}, {});
  done = true;
  session.join();
  EXPECT_GT(frames.load(), 40);
  EXPECT_EQ(missing.load(), 0);
  EXPECT_EQ(catalogue.Snapshot()->Find(mug)->model().views.size(), 48u);
}

// The store as the catalogue sees it, with another user of the same file who deletes every
// object right after the catalogue's write commits: the interleaving a second process (an
// `orbit delete --db` beside a running server) can produce.
class StoreWithAnotherUser : public ModelStore {
 public:
  explicit StoreWithAnotherUser(const std::filesystem::path& file)
      : mine_(file, Create()), other_(file) {}

  ObjectId Enroll(const Enrollment& enrollment) override {
    const ObjectId id = mine_.Enroll(enrollment);
    other_.Delete(id);
    return id;
  }
  void AddViews(ObjectId id, const std::vector<ModelView>& views,
                const std::vector<std::string>& thumbnails) override {
    mine_.AddViews(id, views, thumbnails);
    other_.Delete(id);
  }
  void Delete(ObjectId id) override { mine_.Delete(id); }
  void Rename(ObjectId id, std::string_view name) override { mine_.Rename(id, name); }
  std::vector<ObjectSummary> List(const ListRequest& r) override { return mine_.List(r); }
  std::optional<StoredObject> Get(ObjectId id) override { return mine_.Get(id); }
  std::optional<ObjectSummary> Find(std::string_view name) override { return mine_.Find(name); }
  std::vector<ObjectModel> LoadAll() override { return mine_.LoadAll(); }
  ObjectId ForEachObject(const std::function<void(const StoredObject&)>& visit) override {
    return mine_.ForEachObject(visit);
  }
  void RestoreFrom(ModelStore& source) override { mine_.RestoreFrom(source); }
  void Backup(const std::filesystem::path& to) override { mine_.Backup(to); }

  SqliteModelStore& mine() { return mine_; }

 private:
  SqliteModelStore mine_;
  SqliteModelStore other_;
};

TEST(ModelCatalogueTest, AnObjectDeletedByAnotherStoreUserIsNotFoundAndLeavesTheIndex) {
  ScratchDir dir;
  const auto file = dir / "models.db";
  { SqliteModelStore create(file, Create()); }
  StoreWithAnotherUser store(file);
  // One object enrolled before the other user appears.
  const ObjectId mug = store.mine().Enroll(SyntheticObject("mug", 4));
  ModelCatalogue catalogue(store, DescriptorVariant::kCeddLire, {});
  catalogue.Load();
  ASSERT_NE(catalogue.Snapshot()->Find(mug), nullptr);

  EXPECT_EQ(CodeOf([&] { catalogue.AddViews(mug, {SyntheticView(9, 30)}, {}); }),
            StoreError::Code::kNotFound);
  EXPECT_EQ(catalogue.Snapshot()->Find(mug), nullptr);
  EXPECT_EQ(CodeOf([&] { catalogue.Enroll(SyntheticObject("bowl", 3)); }),
            StoreError::Code::kNotFound);
  EXPECT_EQ(catalogue.Snapshot()->object_count(), 0u);
}

// Reload: what another writer of the store did reaches the index; what the index already holds
// publishes nothing (a replica replaying its own writes makes no session redo work).
TEST(ModelCatalogueTest, ReloadPublishesOnlyWhatAnotherWriterChanged) {
  ScratchDir dir;
  SqliteModelStore store(dir / "models.db", Create());
  SqliteModelStore other_writer(dir / "models.db");
  ModelCatalogue catalogue(store, DescriptorVariant::kCeddLire, {});
  catalogue.Load();
  const ObjectSummary mug = catalogue.Enroll(SyntheticObject("mug", 4));
  const std::uint64_t after_enroll = catalogue.Snapshot()->serial();

  EXPECT_FALSE(catalogue.Reload(mug.id));  // our own write, replayed
  EXPECT_EQ(catalogue.Snapshot()->serial(), after_enroll);

  other_writer.AddViews(mug.id, {SyntheticView(50, 200)});
  const ObjectId jar = other_writer.Enroll(SyntheticObject("jar", 3, 20));
  EXPECT_EQ(catalogue.Snapshot()->Find(jar), nullptr);  // not followed yet
  EXPECT_TRUE(catalogue.Reload(mug.id));
  EXPECT_TRUE(catalogue.Reload(jar));
  EXPECT_EQ(catalogue.Snapshot()->Find(mug.id)->model().views.size(), 5u);
  EXPECT_EQ(catalogue.Snapshot()->Find(jar)->model().name, "jar");

  other_writer.Rename(jar, "pot");
  EXPECT_TRUE(catalogue.Reload(jar));
  EXPECT_EQ(catalogue.Snapshot()->Find(jar)->model().name, "pot");

  other_writer.Delete(mug.id);
  EXPECT_TRUE(catalogue.Reload(mug.id));
  EXPECT_EQ(catalogue.Snapshot()->Find(mug.id), nullptr);
  EXPECT_FALSE(catalogue.Reload(mug.id));  // gone from both: nothing to do
  EXPECT_EQ(catalogue.Snapshot()->object_count(), 1u);
}

}  // namespace
}  // namespace orbit::server
