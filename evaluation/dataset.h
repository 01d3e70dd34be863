// Datasets of object views on disk: the images `orbit import` turns into a model set and
// `orbit eval` runs the evaluation protocol on (docs/design.md#datasets).
//
// Two layouts:
//   coil100   a folder of files objN__A.png (COIL-100: object N, azimuth A degrees);
//   manifest  a CSV file with columns path,object,azimuth and an optional elevation column.
// SelectDataset picks the known and unknown objects of either, as both commands select them.
//
// All functions are thread-safe (they share no state); errors are thrown as described.
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <opencv2/core.hpp>

namespace orbit {

// A rectangle of an image in pixels: where the object is (a tracker's or an annotator's box).
struct ImageBox {
  int x = 0, y = 0;           // top-left corner
  int width = 0, height = 0;  // > 0
  std::string origin;         // where it was given, "FILE:LINE", which messages about it name

  friend bool operator==(const ImageBox&, const ImageBox&) = default;
};

// One image of one object, at a known orientation.
struct DatasetImage {
  std::string path;                 // image file; absolute, or relative to the working directory
  std::string object;               // object name, e.g. "obj7"; images of one object share it
  double azimuth = 0;               // degrees, normalised to [0, 360)
  std::optional<double> elevation;  // degrees, when the dataset records it
  // The object's box as the dataset gives it, when it has boxes (AttachBoxes), and the margin
  // grown around it: the image is described in ObjectRegion(box, box_margin)
  // (client/object_region.h), as a device describes its tracker's box. Empty: the whole image.
  std::optional<ImageBox> box;
  double box_margin = 0;

  friend bool operator==(const DatasetImage&, const DatasetImage&) = default;
};

// Parses an object selection such as "1-20", "7" or "1-5,9": comma-separated numbers and
// inclusive ranges "a-b" (a <= b), numbers from 1. Spaces around items are allowed.
// Returns the selected numbers sorted ascending, each once (overlapping items are merged).
//
// Throws std::invalid_argument, quoting the offending item, for empty text, an empty item, a
// non-number, 0, a reversed range ("5-1"), a range of more than a million numbers, or a number
// too large for int; and quoting the text when its items together select more than a million
// numbers.
std::vector<int> ParseObjectRange(std::string_view text);

// Lists the COIL-100 images in `dir`: every file named objN__A.png (N >= 1 and A integers),
// object name "obj<N>", azimuth A, no elevation; other files are ignored. Sorted by object number,
// then azimuth (numerically, so obj2 precedes obj10 and 5 degrees precede 10).
// When `objects` is given (see ParseObjectRange), only those object numbers are listed.
//
// Throws std::runtime_error naming the folder when it is not a readable directory, when it holds
// no objN__A.png file, or when a selected object has no image there.
std::vector<DatasetImage> ListCoil100(
    const std::filesystem::path& dir,
    const std::optional<std::vector<int>>& objects = std::nullopt);

// Reads a manifest: a CSV file whose first row is a header naming the columns path, object,
// azimuth and optionally elevation and the object's box x, y, w, h (all four or none; whole
// pixels, as boxes.csv's), in any order (no other column is allowed). An image with a box is
// described in ObjectRegion(box, kDefaultBoxMargin) unless a command sets another margin
// (SetBoxMargin). Fields may be
// quoted with "..." ("" inside quotes is one quote); spaces around unquoted fields are trimmed;
// blank lines and CRLF line ends are accepted. A relative path resolves against the folder that
// holds the CSV file; an empty elevation field means "not recorded". Images keep the file's order.
//
// Throws std::runtime_error "FILE:LINE: problem" when the file cannot be read, the header is
// missing, incomplete or has an unknown or repeated column, a row has the wrong number of
// fields, a path or object is empty, an azimuth or elevation is not a finite number, or the
// header names some of x, y, w and h but not all, or a box's field is not a whole number (x, y
// at least 0; w, h at least 1); and
// "FILE: no images" when there are no data rows. Image files are not opened here.
std::vector<DatasetImage> ReadManifest(const std::filesystem::path& csv);

// Reads boxes: a CSV file whose header names path, x, y, w and h (`path,x,y,w,h`, as
// eth-80-dev's and epfl-cars' boxes.csv), paths resolved as the manifest's. Returns each
// resolved path's box, its origin "FILE:LINE". Throws std::runtime_error "FILE:LINE: problem"
// as ReadManifest does, and for a coordinate that is not a whole number, a width or height
// below 1, or a path given twice.
std::map<std::string, ImageBox> ReadBoxes(const std::filesystem::path& csv);

// Gives every image its box from `boxes` (ReadBoxes' keys) and the margin grown around it when
// it is described (ObjectRegion, client/object_region.h: 0.1 adds 10% of the box's width on
// the left and on the right and of its height above and below). Throws std::invalid_argument
// naming the first image that has no box or that has one from its manifest already, or as
// CheckBoxMargin for a margin outside 0..1.
void AttachBoxes(std::vector<DatasetImage>& images, const std::map<std::string, ImageBox>& boxes,
                 double margin);

// Sets the margin of every image that has a box (from its manifest) to `margin`. Throws
// std::invalid_argument as CheckBoxMargin does.
void SetBoxMargin(std::vector<DatasetImage>& images, double margin);

// The region of `image`, whose pixels are `size`, that is described: ObjectRegion
// (client/object_region.h) of its box grown by its margin, named by the box's origin in
// messages; the whole image when it has no box. Throws std::invalid_argument as ObjectRegion
// does for a box not inside the image.
cv::Rect DescribedRegion(const DatasetImage& image, cv::Size size);

// Checks every image's box against the image's size as its file's header states it (nothing is
// decoded), so that a command refuses a bad box before it computes or writes anything. Throws
// std::invalid_argument as ObjectRegion does, naming the box's origin; std::runtime_error as
// ReadImageSize does for an image file it cannot read.
void CheckBoxes(const std::vector<DatasetImage>& images);

// Reads the image file and returns what is described of it: the object's region
// (ObjectRegion of its box) when it has a box, else the whole image. Throws as ReadImageFile
// (client/image_file.h) and ObjectRegion do.
cv::Mat ReadDescribedRegion(const DatasetImage& image);

// One frame of a query capture (`orbit eval --queries`): what a user's own camera took of an
// object, to be recognised against a model set. Consecutive frames of one sequence form one
// query, in the file's order.
struct CaptureFrame {
  std::string path;               // image file, resolved as the manifest's paths are
  std::string object;             // the object it shows; a name absent from the model set: unknown
  std::optional<double> azimuth;  // degrees as the device read them; empty: no sensor
  std::string sequence;           // the query it belongs to
  std::string origin;             // where it was given, "FILE:LINE", which messages about it name

  friend bool operator==(const CaptureFrame&, const CaptureFrame&) = default;
};

// Reads query captures: a CSV file whose header names path, object, sequence and optionally
// azimuth, in any order, with the manifest's rules otherwise (ReadManifest); an empty azimuth
// field means "no reading". Each frame's origin is its row, "FILE:LINE". Throws
// std::runtime_error as ReadManifest does ("FILE:LINE: problem", "empty sequence" too), and
// "FILE: no frames" when there are no data rows.
std::vector<CaptureFrame> ReadQueryCaptures(const std::filesystem::path& csv);

// One query of a capture file: a sequence's object and its frames' positions in the captures,
// in file order.
struct CaptureSequence {
  std::string name;
  std::string object;
  std::vector<std::size_t> frames;

  friend bool operator==(const CaptureSequence&, const CaptureSequence&) = default;
};

// Groups `captures` by sequence: sequences in order of first appearance. Throws
// std::invalid_argument naming the sequence when its frames show more than one object.
std::vector<CaptureSequence> GroupCaptureSequences(const std::vector<CaptureFrame>& captures);

// Reads the frame's image file (ReadImageFile, client/image_file.h); an image that cannot be
// read is reported after the frame's origin ("FILE:LINE: "), when it has one, since its path
// may be named relative to the capture file's folder.
cv::Mat ReadCaptureImage(const CaptureFrame& frame);

// The captured frames as dataset images, in their order (path and object), each with its box
// from `boxes` (AttachBoxes: every frame must have one) grown by `margin` when `boxes` is not
// empty, so that a frame is described in its box as a model view with a box is
// (DescribedRegion). Throws std::invalid_argument as AttachBoxes does.
std::vector<DatasetImage> CaptureImages(const std::vector<CaptureFrame>& captures,
                                        const std::map<std::string, ImageBox>& boxes,
                                        double margin);

// One object of a dataset: the images sharing a name.
struct DatasetObject {
  std::string name;
  std::vector<std::size_t> images;  // positions in the image list, ascending

  friend bool operator==(const DatasetObject&, const DatasetObject&) = default;
};

// Groups `images` by object name: objects in order of first appearance, each with the positions
// of its images. Empty for no images.
std::vector<DatasetObject> GroupByObject(const std::vector<DatasetImage>& images);

// Which images of a dataset a command uses, as `orbit eval` and `orbit import` take them.
// Objects are numbered from 1: in a coil100 folder by the N of objN; in a manifest by order of
// first appearance.
struct DatasetSelection {
  // "coil100": the folder `data`; "manifest": the file `manifest`; "": the layout of whichever
  // of the two is given (coil100 when neither is)
  std::string layout = "coil100";
  std::filesystem::path data;      // the COIL-100 folder (coil100)
  std::filesystem::path manifest;  // the manifest CSV file (manifest)
  std::string objects;             // the known objects (ParseObjectRange); "": all not unknown
  std::string unknown_objects;     // objects left out of the model set (ParseObjectRange); "": none
};

// The images a selection names: those of the known objects and those of the unknown ones, each
// in the dataset's order (ListCoil100's, or the manifest's).
struct SelectedImages {
  std::vector<DatasetImage> known;
  std::vector<DatasetImage> unknown;
};

// Lists the dataset and keeps the selected objects.
//
// Throws std::invalid_argument as ParseObjectRange does, and
//   "object N is in both --objects and --unknown-objects",
//   "--layout coil100 needs --data DIR" (saying that a --manifest goes with --layout manifest
//   when one was given), "--layout manifest needs --manifest FILE", "give --data DIR ... or
//   --manifest FILE ..., not both" (no layout named),
//   "object N selected, but the manifest has M objects" (N the largest number selected),
//   "unknown layout \"L\"";
// std::runtime_error as ListCoil100 (a selected object without images) and ReadManifest do.
SelectedImages SelectDataset(const DatasetSelection& selection);

}  // namespace orbit
