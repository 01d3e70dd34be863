#include "evaluation/dataset.h"

#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "client/object_region.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

using ::testing::ElementsAre;
using testing::ErrorMessageOf;
using ::testing::HasSubstr;
using testing::ScratchDir;

TEST(ParseObjectRangeTest, AcceptsNumbersRangesAndLists) {
  EXPECT_THAT(ParseObjectRange("7"), ElementsAre(7));
  EXPECT_THAT(ParseObjectRange("1-5,9"), ElementsAre(1, 2, 3, 4, 5, 9));
  EXPECT_EQ(ParseObjectRange("1-20").size(), 20u);
  EXPECT_EQ(ParseObjectRange("1-20").back(), 20);
  // Sorted, overlaps merged, spaces tolerated.
  EXPECT_THAT(ParseObjectRange(" 9, 3-4 ,4,2 - 3"), ElementsAre(2, 3, 4, 9));
}

TEST(ParseObjectRangeTest, RangesUpToTheLargestIntAndAMillionNumbers) {
  // A range ending at INT_MAX once counted past it (signed overflow; in practice an endless
  // loop filling memory). Found by fuzz/manifest_fuzzer.cc.
  EXPECT_THAT(ParseObjectRange("2147483647-2147483647"), ElementsAre(2147483647));
  EXPECT_THAT(ParseObjectRange("2147483645-2147483647, 2147483646"),
              ElementsAre(2147483645, 2147483646, 2147483647));
  // A million numbers is the most a selection holds, in one range or in several.
  const std::vector<int> million = ParseObjectRange("1-1000000");
  ASSERT_EQ(million.size(), 1000000u);
  EXPECT_EQ(million.front(), 1);
  EXPECT_EQ(million.back(), 1000000);
  EXPECT_EQ(ParseObjectRange("1-600000,400001-1000000").size(), 1000000u);
  EXPECT_THAT(ErrorMessageOf([] { ParseObjectRange("1-600000,600001-1000001"); }),
              HasSubstr("selects more than a million objects"));
  EXPECT_THAT(ErrorMessageOf([] { ParseObjectRange("1-1000001"); }), HasSubstr("too large"));
}

TEST(ParseObjectRangeTest, RejectsMalformedSelectionsNamingTheItem) {
  EXPECT_THAT(ErrorMessageOf([] { ParseObjectRange(""); }), HasSubstr("empty"));
  EXPECT_THAT(ErrorMessageOf([] { ParseObjectRange("1,,3"); }), HasSubstr("empty item"));
  EXPECT_THAT(ErrorMessageOf([] { ParseObjectRange("1-5,x"); }), HasSubstr("\"x\""));
  EXPECT_THAT(ErrorMessageOf([] { ParseObjectRange("0-3"); }), HasSubstr("numbered from 1"));
  EXPECT_THAT(ErrorMessageOf([] { ParseObjectRange("5-1"); }),
              HasSubstr("\"5-1\" ends before it starts"));
  EXPECT_THAT(ErrorMessageOf([] { ParseObjectRange("1-"); }), HasSubstr("\"1-\""));
  EXPECT_THAT(ErrorMessageOf([] { ParseObjectRange("99999999999"); }), HasSubstr("too large"));
  EXPECT_THAT(ErrorMessageOf([] { ParseObjectRange("1-1000000000"); }), HasSubstr("too large"));
}

TEST(BoxesTest, Eth80BoxesAreAttachedAndDescribedGrownByTheMargin) {
  const auto folder = testing::DataDir() / "eth-80-dev";
  const std::map<std::string, ImageBox> boxes = ReadBoxes(folder / "boxes.csv");
  EXPECT_EQ(boxes.size(), 40u * 41u);  // every view of all.csv
  std::vector<DatasetImage> ring = ReadManifest(folder / "ring.csv");
  ASSERT_EQ(ring.size(), 640u);
  AttachBoxes(ring, boxes, 0.1);
  // The first ring view, images/apple1-090-000.jpg, boxed 32,32,192,191 on line 27 of
  // boxes.csv, described grown by round(19.2) = 19 and round(19.1) = 19 a side.
  const ImageBox expected{32, 32, 192, 191, (folder / "boxes.csv").string() + ":27"};
  EXPECT_EQ(boxes.at((folder / "images/apple1-090-000.jpg").lexically_normal().string()), expected);
  ASSERT_TRUE(ring[0].box.has_value());
  EXPECT_EQ(*ring[0].box, expected);
  EXPECT_EQ(ring[0].box_margin, 0.1);
  EXPECT_EQ(DescribedRegion(ring[0], {256, 256}), cv::Rect(13, 13, 230, 229));
  for (const DatasetImage& image : ring) EXPECT_TRUE(image.box.has_value()) << image.path;
  CheckBoxes(ring);  // every box lies inside its image
}

TEST(BoxesTest, ABoxFileIsCheckedLineByLineAndEveryImageNeedsABox) {
  ScratchDir dir;
  const auto file = dir.Write("boxes.csv", "path,x,y,w,h\na.png,1,2,30,40\n");
  const std::map<std::string, ImageBox> boxes = ReadBoxes(file);
  ASSERT_EQ(boxes.size(), 1u);
  EXPECT_EQ(boxes.begin()->second, (ImageBox{1, 2, 30, 40, file.string() + ":2"}));
  std::vector<DatasetImage> images{{(dir / "a.png").string(), "a", 0, {}, {}}};
  AttachBoxes(images, boxes, 0.25);  // 7.5 -> 8 and 10 a side, clipped at 0
  EXPECT_EQ(images[0].box, boxes.begin()->second);
  EXPECT_EQ(DescribedRegion(images[0], {100, 100}), cv::Rect(0, 0, 39, 52));
  EXPECT_EQ(ErrorMessageOf([&] {
              DescribedRegion(images[0], {20, 100});
            }),
            file.string() + ":2: x+w must be at most the image's width 20");
  // A box given twice (a manifest's and a file's) is refused, naming both places.
  EXPECT_EQ(ErrorMessageOf([&] { AttachBoxes(images, boxes, 0.1); }),
            file.string() + ":2: " + (dir / "a.png").string() + " has a box already (" +
                file.string() + ":2): give boxes in the manifest or in a boxes file, not both");
  images[0].box.reset();
  images.push_back({(dir / "b.png").string(), "b", 0, {}, {}});
  EXPECT_EQ(ErrorMessageOf([&] { AttachBoxes(images, boxes, 0.1); }),
            "no box for " + (dir / "b.png").string());
  EXPECT_EQ(ErrorMessageOf([&] { AttachBoxes(images, boxes, 1.5); }),
            "box margin must be in 0..1, got 1.500000");

  const auto bad = dir.Write("bad.csv", "path,x,y,w,h\na.png,1,2,0,40\n");
  EXPECT_EQ(ErrorMessageOf<std::runtime_error>([&] { ReadBoxes(bad); }),
            bad.string() + ":2: w must be a whole number of at least 1");
  const auto twice = dir.Write("twice.csv", "path,x,y,w,h\na.png,1,2,3,4\n./a.png,1,2,3,4\n");
  EXPECT_EQ(ErrorMessageOf<std::runtime_error>([&] { ReadBoxes(twice); }),
            twice.string() + ":3: path \"./a.png\" has a box already");
  const auto columns = dir.Write("columns.csv", "path,x,y,w\n");
  EXPECT_THAT(ErrorMessageOf<std::runtime_error>([&] { ReadBoxes(columns); }),
              HasSubstr("header lacks the column \"h\""));
}

TEST(ListCoil100Test, ListsTheSharedDataSortedByObjectThenAzimuth) {
  const auto dir = testing::DataDir() / "coil-100";
  const std::vector<DatasetImage> all = ListCoil100(dir);
  ASSERT_EQ(all.size(), 7200u);
  EXPECT_EQ(all[0].object, "obj1");
  EXPECT_EQ(all[0].azimuth, 0);
  EXPECT_EQ(all[1].azimuth, 5);  // numeric order: 5 before 10, 100, ...
  EXPECT_EQ(all[71].azimuth, 355);
  EXPECT_EQ(all[72].object, "obj2");  // obj2 before obj10
  EXPECT_EQ(all.back().object, "obj100");
  EXPECT_EQ(std::filesystem::path(all[1].path), dir / "obj1__5.png");
  EXPECT_FALSE(all[0].elevation.has_value());

  const std::vector<DatasetImage> some = ListCoil100(dir, ParseObjectRange("3,10"));
  ASSERT_EQ(some.size(), 144u);
  EXPECT_EQ(some[0].object, "obj3");
  EXPECT_EQ(some[72].object, "obj10");
  EXPECT_EQ(std::filesystem::path(some[143].path), dir / "obj10__355.png");
}

TEST(ListCoil100Test, IgnoresOtherFilesAndReportsMissingObjects) {
  ScratchDir dir;
  dir.Write("obj2__10.png", "");
  dir.Write("obj2__5.png", "");
  dir.Write("obj10__0.png", "");
  dir.Write("README.md", "");
  dir.Write("obj3__0.jpg", "");
  dir.Write("obj4_0.png", "");
  const std::vector<DatasetImage> images = ListCoil100(dir.path());
  ASSERT_EQ(images.size(), 3u);
  EXPECT_EQ(images[0], (DatasetImage{(dir.path() / "obj2__5.png").string(), "obj2", 5, {}, {}}));
  EXPECT_EQ(images[1].azimuth, 10);
  EXPECT_EQ(images[2].object, "obj10");

  EXPECT_THAT(ErrorMessageOf<std::runtime_error>([&] {
                ListCoil100(dir.path(), std::vector<int>{2, 3});
              }),
              HasSubstr("no image of object 3"));
  EXPECT_THAT(ErrorMessageOf<std::runtime_error>([&] { ListCoil100(dir.path() / "missing"); }),
              HasSubstr("not a directory"));
  ScratchDir empty;
  EXPECT_THAT(ErrorMessageOf<std::runtime_error>([&] { ListCoil100(empty.path()); }),
              HasSubstr("no COIL-100 images"));
}

TEST(ReadManifestTest, ResolvesRelativePathsAgainstTheCsvFolder) {
  ScratchDir dir;
  const auto csv = dir.Write("sets/cups.csv",
                             "object,azimuth,path,elevation\r\n"
                             "cup, 90 ,views/a.png,10\r\n"
                             "\r\n"
                             "\"mug, blue\",-30,/abs/b.png,\r\n"
                             "cup,450,\"views/c \"\"x\"\".png\",-5.5\r\n");
  const std::vector<DatasetImage> images = ReadManifest(csv);
  ASSERT_EQ(images.size(), 3u);
  EXPECT_EQ(
      images[0],
      (DatasetImage{(dir.path() / "sets" / "views" / "a.png").string(), "cup", 90, 10.0, {}}));
  EXPECT_EQ(images[1], (DatasetImage{"/abs/b.png", "mug, blue", 330, std::nullopt, {}}));
  EXPECT_EQ(images[2].path, (dir.path() / "sets" / "views" / "c \"x\".png").string());
  EXPECT_EQ(images[2].azimuth, 90);
  EXPECT_EQ(images[2].elevation, -5.5);
}

TEST(ReadManifestTest, ElevationColumnIsOptional) {
  ScratchDir dir;
  const auto csv = dir.Write("m.csv", "path,object,azimuth\na.png,box,12.5\n");
  const std::vector<DatasetImage> images = ReadManifest(csv);
  ASSERT_EQ(images.size(), 1u);
  EXPECT_EQ(images[0].azimuth, 12.5);
  EXPECT_FALSE(images[0].elevation.has_value());
}

TEST(ReadManifestTest, BoxColumnsGiveEachImageItsBox) {
  ScratchDir dir;
  const auto csv = dir.Write("m.csv", "h,path,w,object,x,azimuth,y\n20,a.png,30,cup,5,90,7\n");
  const std::vector<DatasetImage> images = ReadManifest(csv);
  ASSERT_EQ(images.size(), 1u);
  ASSERT_TRUE(images[0].box.has_value());
  EXPECT_EQ(*images[0].box, (ImageBox{5, 7, 30, 20, csv.string() + ":2"}));
  EXPECT_EQ(images[0].box_margin, kDefaultBoxMargin);
  std::vector<DatasetImage> margined = images;
  SetBoxMargin(margined, 0.25);
  EXPECT_EQ(margined[0].box_margin, 0.25);
  EXPECT_THROW(SetBoxMargin(margined, 1.5), std::invalid_argument);

  const auto error = [&](const std::string& text) {
    const auto bad = dir.Write("bad.csv", text);
    return ErrorMessageOf<std::runtime_error>([&] { ReadManifest(bad); });
  };
  EXPECT_THAT(error("path,object,azimuth,x,y,w\na.png,cup,0,1,2,3\n"),
              HasSubstr(":2: a box needs the four columns x, y, w and h"));
  EXPECT_THAT(error("path,object,azimuth,x,y,w,h\na.png,cup,0,1,2,0,4\n"),
              HasSubstr(":2: w must be a whole number of at least 1"));
  EXPECT_THAT(error("path,object,azimuth,x,y,w,h\na.png,cup,0,1.5,2,3,4\n"),
              HasSubstr(":2: x must be a whole number of at least 0"));
}

TEST(ReadManifestTest, ErrorsNameTheFileAndLine) {
  ScratchDir dir;
  const auto error = [&](const std::string& text) {
    const auto csv = dir.Write("bad.csv", text);
    return ErrorMessageOf<std::runtime_error>([&] { ReadManifest(csv); });
  };
  const std::string name = (dir.path() / "bad.csv").string();
  EXPECT_THAT(error("path,object\na.png,x\n"),
              HasSubstr(name + ":1: header lacks the column \"azimuth\""));
  EXPECT_THAT(error("a.png,x,5\n"), HasSubstr(":1: unknown column \"a.png\""));
  EXPECT_THAT(error("path,object,azimuth,azimuth\n"),
              HasSubstr(":1: column \"azimuth\" appears twice"));
  EXPECT_THAT(error("path,object,azimuth\na.png,x,5\nb.png,x\n"),
              HasSubstr(name + ":3: expected 3 fields, found 2"));
  EXPECT_THAT(error("path,object,azimuth\na.png,x,north\n"),
              HasSubstr(":2: azimuth \"north\" is not a finite number"));
  EXPECT_THAT(error("path,object,azimuth\na.png,x,nan\n"), HasSubstr(":2: azimuth \"nan\""));
  EXPECT_THAT(error("path,object,azimuth,elevation\na.png,x,1,up\n"),
              HasSubstr(":2: elevation \"up\" is not a finite number"));
  EXPECT_THAT(error("path,object,azimuth\n\n,x,1\n"), HasSubstr(":3: empty path"));
  EXPECT_THAT(error("path,object,azimuth\na.png,,1\n"), HasSubstr(":2: empty object name"));
  EXPECT_THAT(error("path,object,azimuth\n\"a.png,x,1\n"), HasSubstr(":2: malformed quotes"));
  EXPECT_THAT(error("path,object,azimuth\n"), HasSubstr(name + ": no images"));
  EXPECT_THAT(error(""), HasSubstr("no header row"));
  EXPECT_THAT(ErrorMessageOf<std::runtime_error>([&] { ReadManifest(dir.path() / "none.csv"); }),
              HasSubstr("cannot read"));
}

TEST(ReadQueryCapturesTest, ReadsSequencesWithOrWithoutAzimuths) {
  ScratchDir dir;
  const auto csv = dir.Write("q.csv",
                             "sequence,path,object,azimuth\n"
                             "walk1,f0.png,mug,12.5\n"
                             "walk1,/abs/f1.png,mug,\n"
                             "\"walk, 2\",f2.png,cup,-30\n");
  const std::vector<CaptureFrame> frames = ReadQueryCaptures(csv);
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_EQ(frames[0], (CaptureFrame{(dir.path() / "f0.png").string(), "mug", 12.5, "walk1",
                                     csv.string() + ":2"}));
  EXPECT_EQ(frames[1],
            (CaptureFrame{"/abs/f1.png", "mug", std::nullopt, "walk1", csv.string() + ":3"}));
  EXPECT_EQ(frames[2].sequence, "walk, 2");
  EXPECT_EQ(frames[2].azimuth, -30);  // as the device read it: only differences matter
  // No azimuth column at all: a device without an orientation sensor.
  EXPECT_FALSE(ReadQueryCaptures(dir.Write("n.csv", "path,object,sequence\na.png,x,s\n"))[0]
                   .azimuth.has_value());
}

TEST(ReadQueryCapturesTest, ErrorsNameTheFileAndLine) {
  ScratchDir dir;
  const auto error = [&](const std::string& text) {
    const auto csv = dir.Write("bad.csv", text);
    return ErrorMessageOf<std::runtime_error>([&] { ReadQueryCaptures(csv); });
  };
  EXPECT_THAT(error("path,object,azimuth\na.png,x,5\n"),
              HasSubstr(":1: header lacks the column \"sequence\" (expected "
                        "path,object,sequence[,azimuth])"));
  EXPECT_THAT(error("path,object,sequence,elevation\n"),
              HasSubstr(":1: unknown column \"elevation\""));
  EXPECT_THAT(error("path,object,sequence\na.png,x,\n"), HasSubstr(":2: empty sequence"));
  EXPECT_THAT(error("path,object,sequence,azimuth\na.png,x,s,east\n"),
              HasSubstr(":2: azimuth \"east\" is not a finite number"));
  EXPECT_THAT(error("path,object,sequence\n"), HasSubstr("bad.csv: no frames"));
}

TEST(GroupCaptureSequencesTest, SequencesInOrderOfFirstAppearanceEachOfOneObject) {
  std::vector<CaptureFrame> frames{{"1.png", "mug", 0, "walk1", ""},
                                   {"2.png", "cup", 0, "walk2", ""},
                                   {"3.png", "mug", 20, "walk1", ""}};
  EXPECT_THAT(GroupCaptureSequences(frames), ElementsAre(CaptureSequence{"walk1", "mug", {0, 2}},
                                                         CaptureSequence{"walk2", "cup", {1}}));
  frames.push_back({"4.png", "jar", 40, "walk1", "q.csv:5"});
  EXPECT_EQ(ErrorMessageOf([&] { GroupCaptureSequences(frames); }),
            "sequence \"walk1\" shows two objects (\"mug\" and \"jar\")");
}

TEST(ReadCaptureImageTest, NamesTheRowOfAFrameItCannotRead) {
  ScratchDir dir;
  const CaptureFrame frame{(dir.path() / "gone.png").string(), "mug", 0, "walk1", "q.csv:7"};
  EXPECT_THAT(ErrorMessageOf<std::runtime_error>([&] { ReadCaptureImage(frame); }),
              ::testing::StartsWith("q.csv:7: " + frame.path + ": "));
  EXPECT_EQ(ReadCaptureImage({testing::CoilDir() + "/obj1__0.png", "obj1", 0, "walk1", ""}).cols,
            128);
}

TEST(GroupByObjectTest, ObjectsInOrderOfFirstAppearanceWithTheirPositions) {
  const std::vector<DatasetImage> images{
      {"1.png", "mug", 0, {}, {}}, {"2.png", "cup", 0, {}, {}},  {"3.png", "mug", 90, {}, {}},
      {"4.png", "box", 0, {}, {}}, {"5.png", "cup", 90, {}, {}}, {"6.png", "mug", 180, {}, {}}};
  EXPECT_THAT(GroupByObject(images),
              ElementsAre(DatasetObject{"mug", {0, 2, 5}}, DatasetObject{"cup", {1, 4}},
                          DatasetObject{"box", {3}}));
  EXPECT_TRUE(GroupByObject({}).empty());
}

TEST(SelectDatasetTest, RefusesMissingPathsOverlapsAndNumbersBeyondTheManifest) {
  ScratchDir dir;
  const auto csv = dir.Write("m.csv", "path,object,azimuth\na.png,cup,0\nb.png,mug,0\n");
  const auto error = [](const DatasetSelection& selection) {
    return ErrorMessageOf([&] { SelectDataset(selection); });
  };
  EXPECT_EQ(error({"coil100", "", "", "", ""}), "--layout coil100 needs --data DIR");
  EXPECT_EQ(error({"manifest", "", "", "1-2", ""}), "--layout manifest needs --manifest FILE");
  EXPECT_EQ(error({"manifest", "", csv, "1-3", "3-5"}),
            "object 3 is in both --objects and --unknown-objects");
  EXPECT_EQ(error({"manifest", "", csv, "1,3", ""}),
            "object 3 selected, but the manifest has 2 objects");
  EXPECT_EQ(error({"manifest", "", csv, "", "2-4"}),
            "object 4 selected, but the manifest has 2 objects");
  EXPECT_EQ(error({"folder", dir.path(), "", "", ""}), "unknown layout \"folder\"");
  EXPECT_EQ(error({"coil100", "", csv, "", ""}),
            "--layout coil100 needs --data DIR; a --manifest FILE goes with --layout manifest");
  // No layout named: the one of the file or folder given, not two of them.
  EXPECT_EQ(SelectDataset({"", "", csv, "", ""}).known.size(), 2u);
  EXPECT_EQ(error({"", "", "", "", ""}), "--layout coil100 needs --data DIR");
  EXPECT_EQ(error({"", dir.path(), csv, "", ""}),
            "give --data DIR (a COIL-100 folder) or --manifest FILE (a CSV file), not both");
  EXPECT_THAT(error({"manifest", "", csv, "1-x", ""}), HasSubstr("\"1-x\""));
}

// Manifest objects are numbered 1, 2, ... in order of first appearance; images keep the file's
// order.
TEST(SelectDatasetTest, SelectsManifestObjectsByNumber) {
  ScratchDir dir;
  const auto csv = dir.Write("m.csv",
                             "path,object,azimuth\n"
                             "/a.png,cup,0\n/b.png,mug,0\n/c.png,cup,90\n"
                             "/d.png,box,0\n/e.png,mug,90\n");
  const auto paths = [](const std::vector<DatasetImage>& images) {
    std::vector<std::string> result;
    for (const DatasetImage& image : images) result.push_back(image.path);
    return result;
  };

  SelectedImages selected = SelectDataset({"manifest", "", csv, "1,3", ""});
  EXPECT_THAT(paths(selected.known), ElementsAre("/a.png", "/c.png", "/d.png"));
  EXPECT_TRUE(selected.unknown.empty());

  selected = SelectDataset({"manifest", "", csv, "", "2"});  // known: every other object
  EXPECT_THAT(paths(selected.known), ElementsAre("/a.png", "/c.png", "/d.png"));
  EXPECT_THAT(paths(selected.unknown), ElementsAre("/b.png", "/e.png"));

  selected = SelectDataset({"manifest", "", csv, "3", "1"});
  EXPECT_THAT(paths(selected.known), ElementsAre("/d.png"));
  EXPECT_THAT(paths(selected.unknown), ElementsAre("/a.png", "/c.png"));

  selected = SelectDataset({"manifest", "", csv, "", ""});
  EXPECT_EQ(selected.known, ReadManifest(csv));
}

TEST(SelectDatasetTest, SelectsCoil100ObjectsByTheirNumber) {
  ScratchDir dir;
  for (const char* name : {"obj1__0.png", "obj1__5.png", "obj2__0.png", "obj10__0.png"}) {
    dir.Write(name, "");
  }
  const auto objects = [](const std::vector<DatasetImage>& images) {
    std::vector<std::string> result;
    for (const DatasetImage& image : images) result.push_back(image.object);
    return result;
  };

  SelectedImages selected = SelectDataset({"coil100", dir.path(), "", "", "2"});
  EXPECT_THAT(objects(selected.known), ElementsAre("obj1", "obj1", "obj10"));
  EXPECT_THAT(objects(selected.unknown), ElementsAre("obj2"));

  selected = SelectDataset({"coil100", dir.path(), "", "1,10", ""});
  EXPECT_THAT(objects(selected.known), ElementsAre("obj1", "obj1", "obj10"));
  EXPECT_TRUE(selected.unknown.empty());

  EXPECT_THAT(ErrorMessageOf<std::runtime_error>([&] {
                SelectDataset({"coil100", dir.path(), "", "3", ""});
              }),
              HasSubstr("no image of object 3"));
}

}  // namespace
}  // namespace orbit
