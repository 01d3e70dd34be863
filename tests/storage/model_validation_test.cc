// Bad input is refused by the store itself, with a message that says what is wrong, and nothing
// is written (ModelStore's contract; docs/design.md#service-behaviour: INVALID_ARGUMENT).
#include "storage/model_validation.h"

#include <functional>
#include <limits>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "storage/sqlite_model_store.h"
#include "tests/support/storage_test_support.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

using orbit::testing::ErrorMessageOf;
using testing::RawDatabase;
using testing::ScratchDir;
using testing::SyntheticObject;
using testing::SyntheticView;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// A store holding one object, "keep", of 3 views; Unchanged() says whether the file still holds
// exactly that, untouched.
class RefusalTest : public ::testing::Test {
 protected:
  RefusalTest() : store_(dir_ / "models.db", {.create_if_missing = true}) {
    keep_ = store_.Enroll(SyntheticObject("keep", 3));
    keep_updated_at_ = store_.Get(keep_)->summary.updated_at;
  }

  void ExpectUnchanged() {
    RawDatabase raw(dir_ / "models.db");
    EXPECT_EQ(raw.Int("SELECT count(*) FROM objects"), 1);
    EXPECT_EQ(raw.Int("SELECT count(*) FROM views"), 3);
    EXPECT_EQ(raw.Text("SELECT name FROM objects"), "keep");
    EXPECT_EQ(raw.Text("SELECT updated_at FROM objects"), keep_updated_at_);
  }

  Enrollment WithView(const ModelView& bad) {
    Enrollment enrollment = SyntheticObject("new", 3);
    enrollment.views[2] = bad;
    return enrollment;
  }

  ScratchDir dir_;
  SqliteModelStore store_;
  ObjectId keep_ = 0;
  std::string keep_updated_at_;
};

TEST_F(RefusalTest, DescriptorValuesOutsideZeroToSeven) {
  ModelView bad = SyntheticView(1, 0);
  bad.descriptor[17] = 9;
  EXPECT_EQ(ErrorMessageOf([&] { store_.Enroll(WithView(bad)); }),
            "view 2: descriptor value 9 at index 17 is outside 0..7");
  bad.descriptor[17] = 0;
  bad.descriptor[143] = 255;
  EXPECT_EQ(ErrorMessageOf([&] {
              store_.AddViews(keep_, {SyntheticView(2, 0), bad});
            }),
            "view 1: descriptor value 255 at index 143 is outside 0..7");
  ExpectUnchanged();
}

TEST_F(RefusalTest, NonFiniteOrOutOfRangeAngles) {
  ModelView bad = SyntheticView(1, kNaN);
  EXPECT_EQ(ErrorMessageOf([&] { store_.Enroll(WithView(bad)); }),
            "view 2: azimuth nan is not a finite number");
  bad.azimuth = -kInf;
  EXPECT_EQ(ErrorMessageOf([&] { store_.AddViews(keep_, {bad}); }),
            "view 0: azimuth -inf is not a finite number");
  bad.azimuth = 10;
  bad.elevation = 90.5;
  EXPECT_EQ(ErrorMessageOf([&] { store_.Enroll(WithView(bad)); }),
            "view 2: elevation 90.500000 is outside [-90, 90] degrees");
  bad.elevation = kNaN;
  EXPECT_EQ(ErrorMessageOf([&] { store_.Enroll(WithView(bad)); }),
            "view 2: elevation nan is outside [-90, 90] degrees");
  ExpectUnchanged();
}

TEST_F(RefusalTest, TypicalDistanceOutsideZeroToOne) {
  ModelView bad = SyntheticView(1, 0);
  bad.typical_distance = 1.5;
  EXPECT_EQ(ErrorMessageOf([&] { store_.Enroll(WithView(bad)); }),
            "view 2: typical distance 1.500000 is outside [0, 1] (a Tanimoto distance)");
  bad.typical_distance = kNaN;
  EXPECT_EQ(ErrorMessageOf([&] { store_.Enroll(WithView(bad)); }),
            "view 2: typical distance nan is outside [0, 1] (a Tanimoto distance)");
  bad.typical_distance = -0.01;
  EXPECT_EQ(ErrorMessageOf([&] { store_.Enroll(WithView(bad)); }),
            "view 2: typical distance -0.010000 is outside [0, 1] (a Tanimoto distance)");
  ExpectUnchanged();
}

TEST_F(RefusalTest, BadNamesOnEnrollAndRename) {
  auto enroll_named = [&](const std::string& name) {
    return ErrorMessageOf([&] { store_.Enroll(SyntheticObject(name, 1)); });
  };
  EXPECT_EQ(enroll_named(""), "object name is empty");
  EXPECT_EQ(enroll_named(std::string(65, 'a')),
            "object name has 65 characters, more than the limit of 64");
  EXPECT_EQ(enroll_named("a/b"),
            "object name \"a/b\" has a character not allowed at position 1 (allowed: ASCII "
            "letters, digits, '_', '-', '.')");
  EXPECT_EQ(enroll_named("m\xc3\xbcg"),  // "müg" in UTF-8
            "object name \"m\xc3\xbcg\" has a character not allowed at position 1 (allowed: "
            "ASCII letters, digits, '_', '-', '.')");
  EXPECT_EQ(enroll_named("red mug"),
            "object name \"red mug\" has a character not allowed at position 3 (allowed: ASCII "
            "letters, digits, '_', '-', '.')");
  EXPECT_EQ(enroll_named("-mug"), "object name \"-mug\" must start with a letter or a digit");
  EXPECT_EQ(ErrorMessageOf([&] { store_.Rename(keep_, "x;DROP TABLE objects"); }),
            "object name \"x;DROP TABLE objects\" has a character not allowed at position 1 "
            "(allowed: ASCII letters, digits, '_', '-', '.')");
  store_.Enroll(SyntheticObject(std::string(64, 'z'), 1));  // the longest name is fine
  store_.Delete(store_.Find(std::string(64, 'z'))->id);
  ExpectUnchanged();
}

TEST_F(RefusalTest, TooFewOrTooManyViewsAndMismatchedThumbnails) {
  EXPECT_EQ(ErrorMessageOf([&] { store_.Enroll(SyntheticObject("empty", 0)); }),
            "no views: an object needs at least one view");
  EXPECT_EQ(ErrorMessageOf([&] { store_.Enroll(SyntheticObject("huge", 1025)); }),
            "1025 views, more than the limit of 1024 per object");
  Enrollment thumbs = SyntheticObject("thumbs", 3);
  thumbs.thumbnails = {"a", "b"};
  EXPECT_EQ(ErrorMessageOf([&] { store_.Enroll(thumbs); }),
            "2 thumbnails for 3 views: give none or one per view");
  thumbs.thumbnails = {"a", std::string(64 * 1024 + 1, 'x'), "c"};
  EXPECT_EQ(ErrorMessageOf([&] { store_.Enroll(thumbs); }),
            "view 1: thumbnail of 65537 bytes is larger than the limit of 65536");
  ExpectUnchanged();
}

TEST_F(RefusalTest, MetadataThatIsNotAJsonObject) {
  Enrollment enrollment = SyntheticObject("meta", 1);
  enrollment.metadata = "{\"colour\": ";
  EXPECT_EQ(ErrorMessageOf([&] { store_.Enroll(enrollment); }), "metadata is not valid JSON");
  enrollment.metadata = "[1, 2]";
  EXPECT_EQ(ErrorMessageOf([&] { store_.Enroll(enrollment); }),
            "metadata must be a JSON object ({...})");
  enrollment.metadata = "{\"x\": \"" + std::string(16 * 1024, 'y') + "\"}";
  EXPECT_EQ(ErrorMessageOf([&] { store_.Enroll(enrollment); }),
            "metadata of 16393 bytes is larger than the limit of 16384");
  ExpectUnchanged();
}

// Nesting the stores' JSON functions would refuse (the review's case came back INTERNAL with the
// INSERT statement's text) is refused here, by its depth; brackets inside strings do not count.
TEST_F(RefusalTest, MetadataNestedTooDeep) {
  Enrollment enrollment = SyntheticObject("deep", 1);
  enrollment.metadata = "{\"a\": " + std::string(40, '[') + std::string(40, ']') + "}";
  EXPECT_EQ(ErrorMessageOf([&] { store_.Enroll(enrollment); }),
            "metadata nests objects and arrays 41 deep, more than the limit of 32");
  enrollment.metadata = "{\"a\": " + std::string(31, '[') + std::string(31, ']') + "}";
  EXPECT_NO_THROW(store_.Enroll(enrollment));
  Enrollment quoted = SyntheticObject("quoted", 1);
  quoted.metadata = "{\"note\": \"" + std::string(100, '[') + "\\\"{\"}";
  EXPECT_NO_THROW(store_.Enroll(quoted));
}

}  // namespace
}  // namespace orbit
