// ModelStore's contracts (storage/model_store.h) as a user of any store sees them, run on both
// implementations (tests/support/model_store_backends.h): what goes in comes out, ids, names,
// paging, deletes, what survives closing and reopening, whole objects for readers while
// another store instance writes, one snapshot for a walk over every object, and restoring one
// store into another.
#include "storage/model_store.h"

#include <atomic>
#include <chrono>
#include <memory>
#include <regex>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "storage/store_error.h"
#include "tests/support/model_store_backends.h"
#include "tests/support/storage_test_support.h"

namespace orbit {
namespace {

using ::testing::ElementsAre;
using testing::StoreErrorOf;
using testing::SyntheticObject;
using testing::SyntheticView;

std::vector<double> Azimuths(const std::vector<ModelView>& views) {
  std::vector<double> azimuths;
  for (const ModelView& view : views) azimuths.push_back(view.azimuth);
  return azimuths;
}

template <typename Backend>
class ModelStoreTest : public ::testing::Test {
 protected:
  Backend backend_;
  std::unique_ptr<ModelStore> store_ = backend_.Open();
};

using Backends = ::testing::Types<testing::SqliteBackend, testing::PostgresBackend>;
TYPED_TEST_SUITE(ModelStoreTest, Backends, testing::BackendName);

TYPED_TEST(ModelStoreTest, GetReturnsTheEnrolledObjectWithViewsOrderedByAzimuth) {
  ModelStore& store = *this->store_;
  Enrollment mug;
  mug.name = "red-mug_2.v1";
  mug.variant = DescriptorVariant::kCeddFull;
  mug.views = {SyntheticView(1, 370), SyntheticView(2, -90), SyntheticView(3, 0)};
  mug.views[1].elevation = -12.5;
  mug.views[2].typical_distance = 0.25;
  mug.views[0].typical_distance = 0.1;  // not a binary fraction: must come back bit for bit
  mug.thumbnails = {"jpeg-bytes-1", "", std::string("\0\x01\x02", 3)};
  mug.metadata = R"({"colour": "red", "shelf": 3})";

  const ObjectId id = store.Enroll(mug);
  const std::optional<StoredObject> stored = store.Get(id);

  ASSERT_TRUE(stored.has_value());
  EXPECT_EQ(stored->summary.id, id);
  EXPECT_EQ(stored->summary.name, "red-mug_2.v1");
  EXPECT_EQ(stored->summary.variant, DescriptorVariant::kCeddFull);
  EXPECT_EQ(stored->summary.view_count, 3);
  EXPECT_EQ(stored->summary.metadata, R"({"colour": "red", "shelf": 3})");
  EXPECT_TRUE(std::regex_match(stored->summary.created_at,
                               std::regex(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\.\d{3}Z)")))
      << stored->summary.created_at;
  EXPECT_EQ(stored->summary.updated_at, stored->summary.created_at);
  // 370 -> 10 and -90 -> 270; ordered 0, 10, 270: views 3, 1, 2 as enrolled.
  EXPECT_THAT(Azimuths(stored->views), ElementsAre(0.0, 10.0, 270.0));
  EXPECT_EQ(stored->views[0].descriptor, mug.views[2].descriptor);
  EXPECT_EQ(stored->views[1].descriptor, mug.views[0].descriptor);
  EXPECT_EQ(stored->views[2].descriptor, mug.views[1].descriptor);
  EXPECT_EQ(stored->views[0].typical_distance, 0.25);
  EXPECT_EQ(stored->views[1].typical_distance, 0.1);
  EXPECT_EQ(stored->views[0].elevation, std::nullopt);
  EXPECT_EQ(stored->views[2].elevation, -12.5);
  EXPECT_THAT(stored->thumbnails, ElementsAre(std::string("\0\x01\x02", 3), "jpeg-bytes-1", ""));
  EXPECT_EQ(store.Get(id + 1), std::nullopt);
}

TYPED_TEST(ModelStoreTest, EverythingSurvivesClosingAndReopening) {
  const ObjectId cup = this->store_->Enroll(SyntheticObject("cup", 72, 5));
  this->store_->Enroll(SyntheticObject("bowl", 4, 9));
  this->store_.reset();

  const std::unique_ptr<ModelStore> reopened = this->backend_.Open();
  const std::vector<ObjectModel> models = reopened->LoadAll();
  ASSERT_EQ(models.size(), 2u);
  EXPECT_EQ(models[0].id, cup);
  EXPECT_EQ(models[0].name, "cup");
  ASSERT_EQ(models[0].views.size(), 72u);
  EXPECT_EQ(models[0].views[71].azimuth, 355.0);
  EXPECT_EQ(models[0].views[71].descriptor, SyntheticView(5 + 71, 0).descriptor);
  EXPECT_EQ(models[1].name, "bowl");
  EXPECT_EQ(models[1].views.size(), 4u);
}

TYPED_TEST(ModelStoreTest, IdsOfDeletedObjectsAreNeverReused) {
  ModelStore& store = *this->store_;
  const ObjectId a = store.Enroll(SyntheticObject("a", 2));
  const ObjectId b = store.Enroll(SyntheticObject("b", 2));
  store.Delete(b);
  const ObjectId c = store.Enroll(SyntheticObject("c", 2));
  this->store_.reset();
  const ObjectId d = this->backend_.Open()->Enroll(SyntheticObject("d", 2));
  EXPECT_EQ(a, 1);
  EXPECT_EQ(b, 2);
  EXPECT_EQ(c, 3);  // not 2 again: a client still holding 2 must not reach "c"
  EXPECT_EQ(d, 4);  // nor after reopening
}

TYPED_TEST(ModelStoreTest, DeleteRemovesTheObjectAndAllItsViews) {
  ModelStore& store = *this->store_;
  const ObjectId keep = store.Enroll(SyntheticObject("keep", 3));
  const ObjectId gone = store.Enroll(SyntheticObject("gone", 5));

  store.Delete(gone);

  EXPECT_EQ(store.Get(gone), std::nullopt);
  EXPECT_EQ(store.Find("gone"), std::nullopt);
  EXPECT_EQ(this->backend_.Int("SELECT count(*) FROM views"), 3);
  EXPECT_EQ(
      this->backend_.Int("SELECT count(*) FROM views WHERE object_id = " + std::to_string(gone)),
      0);
  const auto [code, message] = StoreErrorOf([&] { store.Delete(gone); });
  EXPECT_EQ(code, StoreError::Code::kNotFound);
  EXPECT_EQ(message, "no object with id 2");
  EXPECT_EQ(store.Get(keep)->views.size(), 3u);
}

TYPED_TEST(ModelStoreTest, RenameMovesTheNameAndRefusesTakenOrUnknown) {
  ModelStore& store = *this->store_;
  const ObjectId mug = store.Enroll(SyntheticObject("mug", 2));
  const ObjectId jar = store.Enroll(SyntheticObject("jar", 2));
  const std::string enrolled_at = store.Get(mug)->summary.updated_at;
  std::this_thread::sleep_for(std::chrono::milliseconds(5));  // timestamps have 1 ms steps

  store.Rename(mug, "cup");

  EXPECT_EQ(store.Find("mug"), std::nullopt);
  ASSERT_TRUE(store.Find("cup").has_value());
  EXPECT_EQ(store.Find("cup")->id, mug);
  EXPECT_EQ(store.Find("cup")->created_at, enrolled_at);
  EXPECT_GT(store.Find("cup")->updated_at, enrolled_at);

  const auto [taken_code, taken] = StoreErrorOf([&] { store.Rename(mug, "jar"); });
  EXPECT_EQ(taken_code, StoreError::Code::kAlreadyExists);
  EXPECT_EQ(taken, "an object named \"jar\" already exists (id 2)");
  EXPECT_EQ(store.Find("jar")->id, jar);
  EXPECT_EQ(StoreErrorOf([&] { store.Rename(99, "plate"); }).first, StoreError::Code::kNotFound);
  EXPECT_EQ(store.Find("plate"), std::nullopt);
  store.Rename(mug, "cup");  // its own name: nothing to do, no error
  EXPECT_EQ(store.Find("cup")->id, mug);
}

TYPED_TEST(ModelStoreTest, EnrollingATakenNameIsRefusedAndWritesNothing) {
  ModelStore& store = *this->store_;
  store.Enroll(SyntheticObject("mug", 3, 1));

  const auto [code, message] = StoreErrorOf([&] { store.Enroll(SyntheticObject("mug", 7, 2)); });

  EXPECT_EQ(code, StoreError::Code::kAlreadyExists);
  EXPECT_EQ(message, "an object named \"mug\" already exists (id 1)");
  EXPECT_EQ(this->backend_.Int("SELECT count(*) FROM objects"), 1);
  EXPECT_EQ(this->backend_.Int("SELECT count(*) FROM views"), 3);
}

TYPED_TEST(ModelStoreTest, AddViewsAppendsAndTouchesUpdatedAt) {
  ModelStore& store = *this->store_;
  const ObjectId id = store.Enroll(SyntheticObject("mug", 2));  // azimuths 0, 180
  const std::string enrolled_at = store.Get(id)->summary.updated_at;
  std::this_thread::sleep_for(std::chrono::milliseconds(5));

  store.AddViews(id, {SyntheticView(40, 90), SyntheticView(41, 450)}, {"t90", "t450"});

  const StoredObject stored = *store.Get(id);
  EXPECT_EQ(stored.summary.view_count, 4);
  EXPECT_THAT(Azimuths(stored.views), ElementsAre(0.0, 90.0, 90.0, 180.0));
  EXPECT_THAT(stored.thumbnails, ElementsAre("", "t90", "t450", ""));
  EXPECT_GT(stored.summary.updated_at, enrolled_at);
  EXPECT_EQ(StoreErrorOf([&] { store.AddViews(id + 1, {SyntheticView(1, 0)}); }).first,
            StoreError::Code::kNotFound);
}

TYPED_TEST(ModelStoreTest, AddViewsBeyondTheLimitPerObjectIsRefusedWhole) {
  ModelStore& store = *this->store_;
  const ObjectId id = store.Enroll(SyntheticObject("mug", 1000));
  const std::vector<ModelView> more = SyntheticObject("x", 25).views;

  try {
    store.AddViews(id, more);
    ADD_FAILURE() << "1025 views accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "object 1 has 1000 views; 25 more would exceed the limit of 1024 per object");
  }
  EXPECT_EQ(store.Get(id)->views.size(), 1000u);
  store.AddViews(id, std::vector<ModelView>(more.begin(), more.begin() + 24));
  EXPECT_EQ(store.Get(id)->views.size(), 1024u);
}

TYPED_TEST(ModelStoreTest, ListPagesThroughObjectsInIdOrderWithViewCounts) {
  ModelStore& store = *this->store_;
  for (int i = 1; i <= 5; ++i) store.Enroll(SyntheticObject("obj" + std::to_string(i), i));

  const std::vector<ObjectSummary> first = store.List({.after_id = 0, .limit = 2});
  ASSERT_EQ(first.size(), 2u);
  EXPECT_EQ(first[0].name, "obj1");
  EXPECT_EQ(first[0].view_count, 1);
  EXPECT_EQ(first[1].name, "obj2");
  EXPECT_EQ(first[1].view_count, 2);
  store.Delete(3);  // between two pages: the listing carries on after the last id it gave
  const std::vector<ObjectSummary> second = store.List({.after_id = first[1].id, .limit = 2});
  ASSERT_EQ(second.size(), 2u);
  EXPECT_EQ(second[0].name, "obj4");
  EXPECT_EQ(second[0].view_count, 4);
  EXPECT_EQ(second[1].name, "obj5");
  EXPECT_TRUE(store.List({.after_id = second[1].id, .limit = 2}).empty());
  EXPECT_THROW(store.List({.after_id = 0, .limit = 0}), std::invalid_argument);
  EXPECT_THROW(store.List({.after_id = 0, .limit = kMaxListLimit + 1}), std::invalid_argument);
}

TYPED_TEST(ModelStoreTest, LoadAllGivesEveryObjectInIdOrderWithItsVariant) {
  ModelStore& store = *this->store_;
  Enrollment full = SyntheticObject("full", 3, 7);
  full.variant = DescriptorVariant::kCeddFull;
  full.views[0].azimuth = 300;  // views: 300, 120, 240 -> loaded as 120, 240, 300
  const ObjectId lire_id = store.Enroll(SyntheticObject("lire", 2, 3));
  const ObjectId full_id = store.Enroll(full);
  store.AddViews(lire_id, {SyntheticView(99, 90)});  // stored after "full"'s views

  const std::vector<ObjectModel> models = store.LoadAll();

  ASSERT_EQ(models.size(), 2u);
  EXPECT_EQ(models[0].id, lire_id);
  EXPECT_EQ(models[0].variant, DescriptorVariant::kCeddLire);
  EXPECT_THAT(Azimuths(models[0].views), ElementsAre(0.0, 90.0, 180.0));
  EXPECT_EQ(models[0].views[1].descriptor, SyntheticView(99, 0).descriptor);
  EXPECT_EQ(models[1].id, full_id);
  EXPECT_EQ(models[1].variant, DescriptorVariant::kCeddFull);
  EXPECT_THAT(Azimuths(models[1].views), ElementsAre(120.0, 240.0, 300.0));
  EXPECT_EQ(models[1].views[2].descriptor, full.views[0].descriptor);
  EXPECT_EQ(models[1].views[2].typical_distance, full.views[0].typical_distance);
}

// Two views of `variant`, an appearance variant, with values in all 480 places.
Enrollment AppearanceObject(const std::string& name, DescriptorVariant variant, int seed) {
  Enrollment object = SyntheticObject(name, 2, seed);
  object.variant = variant;
  for (ModelView& view : object.views) {
    for (int i = kCeddSize; i < kDescriptorSize; ++i) view.descriptor[i] = (i * seed + 1) % 8;
  }
  return object;
}

// A cedd-hsv-layout object (the SQLite store's schema 5, PostgreSQL's 4) and a cedd-soft-hsv-hog
// one (6 and 5) come back each in its own variant with every one of its 480 values.
TYPED_TEST(ModelStoreTest, TheLayoutAndSoftHueVariantsAreStoredAsThemselves) {
  ModelStore& store = *this->store_;
  int seed = 3;
  for (const DescriptorVariant variant :
       {DescriptorVariant::kCeddHsvLayout, DescriptorVariant::kCeddSoftHsvHog}) {
    SCOPED_TRACE(VariantName(variant));
    const Enrollment object = AppearanceObject(std::string(VariantName(variant)), variant, seed++);
    const ObjectId id = store.Enroll(object);
    const std::optional<StoredObject> stored = store.Get(id);
    ASSERT_TRUE(stored.has_value());
    EXPECT_EQ(stored->summary.variant, variant);
    ASSERT_EQ(stored->views.size(), 2u);
    EXPECT_EQ(stored->views[0].descriptor, object.views[0].descriptor);
    EXPECT_EQ(stored->views[1].descriptor, object.views[1].descriptor);
  }
  const std::vector<ObjectModel> loaded = store.LoadAll();
  ASSERT_EQ(loaded.size(), 2u);
  EXPECT_EQ(loaded.at(0).variant, DescriptorVariant::kCeddHsvLayout);
  EXPECT_EQ(loaded.at(1).variant, DescriptorVariant::kCeddSoftHsvHog);
}

// An object of the appearance variant keeps every one of its 480 values, through AddViews too,
// beside an object of a CEDD variant whose 144 values are all that is stored.
TYPED_TEST(ModelStoreTest, AppearanceVariantKeepsItsChannels) {
  ModelStore& store = *this->store_;
  const Enrollment appearance = AppearanceObject("appearance", DescriptorVariant::kCeddHsvHog, 5);
  const ObjectId id = store.Enroll(appearance);
  ModelView added = appearance.views[0];
  added.azimuth = 45;
  added.descriptor[kDescriptorSize - 1] = 2;
  store.AddViews(id, {added});
  const ObjectId lire_id = store.Enroll(SyntheticObject("lire", 1, 9));

  const std::vector<ObjectModel> models = store.LoadAll();
  ASSERT_EQ(models.size(), 2u);
  EXPECT_EQ(models[0].variant, DescriptorVariant::kCeddHsvHog);
  ASSERT_EQ(models[0].views.size(), 3u);
  EXPECT_EQ(models[0].views[0].descriptor, appearance.views[0].descriptor);  // azimuth 0
  EXPECT_EQ(models[0].views[1].descriptor, added.descriptor);                // azimuth 45
  EXPECT_EQ(models[0].views[1].descriptor[kDescriptorSize - 1], 2);
  const std::optional<StoredObject> stored = store.Get(id);
  ASSERT_TRUE(stored.has_value());
  EXPECT_EQ(stored->views[2].descriptor, appearance.views[1].descriptor);
  EXPECT_EQ(models[1].id, lire_id);
  EXPECT_EQ(models[1].views[0].descriptor, SyntheticView(9, 0).descriptor);
  EXPECT_EQ(this->backend_.Int("SELECT count(*) FROM views WHERE length(descriptor) = 480"), 3);
  EXPECT_EQ(this->backend_.Int("SELECT count(*) FROM views WHERE length(descriptor) = 144"), 1);
}

// Two store instances on one store, as two processes (or two server replicas) would have: while
// one enrolls, readers of both see only whole objects, never fewer than before, and every page
// of a listing holds whole objects too.
TYPED_TEST(ModelStoreTest, ReadersOfTwoInstancesSeeWholeObjectsWhileOneWrites) {
  constexpr int kViews = 72;
  constexpr int kObjects = 30;
  ModelStore& store = *this->store_;
  const std::unique_ptr<ModelStore> other = this->backend_.Open();
  std::atomic<bool> writing = true;
  std::atomic<int> loads = 0;

  auto read_until_done = [&](ModelStore& reader) {
    std::size_t last_count = 0;
    while (writing) {
      const std::vector<ObjectModel> models = reader.LoadAll();
      for (std::size_t i = 0; i < models.size(); ++i) {
        EXPECT_EQ(models[i].views.size(), static_cast<std::size_t>(kViews)) << models[i].name;
        if (i > 0) {
          EXPECT_LT(models[i - 1].id, models[i].id);
        }
      }
      for (const ObjectSummary& summary : reader.List({.after_id = 0, .limit = 1000})) {
        EXPECT_EQ(summary.view_count, kViews) << summary.name;
      }
      EXPECT_GE(models.size(), last_count);  // only enrollments here
      last_count = models.size();
      ++loads;
    }
  };
  std::thread same_store(read_until_done, std::ref(store));
  std::thread other_store(read_until_done, std::ref(*other));
  for (int i = 0; i < kObjects; ++i) {
    store.Enroll(SyntheticObject("obj" + std::to_string(i), kViews, i));
  }
  writing = false;
  same_store.join();
  other_store.join();

  EXPECT_GT(loads.load(), 0);
  EXPECT_EQ(other->LoadAll().size(), static_cast<std::size_t>(kObjects));
}

// Every object as ForEachObject hands them over.
std::vector<StoredObject> EveryObject(ModelStore& store) {
  std::vector<StoredObject> objects;
  store.ForEachObject([&](const StoredObject& object) { objects.push_back(object); });
  return objects;
}

// Another instance writes while the walk is half-way: the walk still gives the store as it was
// when it began, every object whole, nothing of the writes.
TYPED_TEST(ModelStoreTest, ForEachObjectGivesOneSnapshotWhileAnotherInstanceWrites) {
  ModelStore& store = *this->store_;
  const ObjectId mug = store.Enroll(SyntheticObject("mug", 3, 1));
  const ObjectId jar = store.Enroll(SyntheticObject("jar", 2, 5));
  const ObjectId pot = store.Enroll(SyntheticObject("pot", 4, 9));
  const std::vector<StoredObject> before = {*store.Get(mug), *store.Get(jar), *store.Get(pot)};

  const std::unique_ptr<ModelStore> other = this->backend_.Open();
  std::vector<StoredObject> seen;
  store.ForEachObject([&](const StoredObject& object) {
    if (seen.empty()) {
      other->Delete(pot);
      other->AddViews(jar, {SyntheticView(40, 123)});
      other->Rename(mug, "cup");
      other->Enroll(SyntheticObject("bowl", 2, 20));
    }
    seen.push_back(object);
  });
  EXPECT_EQ(seen, before);
  EXPECT_EQ(EveryObject(store).size(), 3u);  // after the walk: mug (as cup), jar, bowl
}

// A copy made by RestoreFrom is the same objects under the same ids, with the same times; and the
// id of an object deleted before the copy is never handed out by it, nor by a copy of the copy.
TYPED_TEST(ModelStoreTest, RestoreFromKeepsIdsTimesAndNeverReusesAnId) {
  ModelStore& store = *this->store_;
  Enrollment mug = SyntheticObject("mug", 3, 1);
  mug.metadata = R"({"shelf": 2})";
  mug.thumbnails = {"jpeg-0", "", "jpeg-2"};
  store.Enroll(mug);
  const ObjectId jar = store.Enroll(SyntheticObject("jar", 2, 5));
  store.Delete(store.Enroll(SyntheticObject("pot", 2, 9)));  // id 3, gone
  store.AddViews(jar, {SyntheticView(40, 123)});
  const std::vector<StoredObject> original = EveryObject(store);

  testing::ScratchDir dir;
  SqliteModelStore copy(dir / "copy.db", {.create_if_missing = true});
  copy.RestoreFrom(store);
  EXPECT_EQ(EveryObject(copy), original);

  TypeParam fresh;
  const std::unique_ptr<ModelStore> restored = fresh.Open();
  restored->RestoreFrom(copy);
  EXPECT_EQ(EveryObject(*restored), original);
  EXPECT_EQ(restored->Enroll(SyntheticObject("bowl", 2, 20)), 4);  // not 3 again
  EXPECT_EQ(copy.Enroll(SyntheticObject("bowl", 2, 20)), 4);
}

TYPED_TEST(ModelStoreTest, RestoreIntoAStoreThatHoldsObjectsIsRefusedAndWritesNothing) {
  ModelStore& store = *this->store_;
  store.Enroll(SyntheticObject("mug", 2));
  testing::ScratchDir dir;
  SqliteModelStore backup(dir / "backup.db", {.create_if_missing = true});
  backup.Enroll(SyntheticObject("jar", 2, 5));

  const auto [code, message] = StoreErrorOf([&] { store.RestoreFrom(backup); });
  EXPECT_EQ(code, StoreError::Code::kAlreadyExists);
  EXPECT_THAT(message, ::testing::HasSubstr("holds 1 objects: restore into an empty store"));
  ASSERT_EQ(EveryObject(store).size(), 1u);
  EXPECT_EQ(EveryObject(store)[0].summary.name, "mug");
}

}  // namespace
}  // namespace orbit
