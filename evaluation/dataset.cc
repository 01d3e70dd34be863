#include "evaluation/dataset.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <regex>
#include <set>
#include <stdexcept>
#include <system_error>
#include <tuple>

#include "client/image_file.h"
#include "client/object_region.h"
#include "core/base/angles.h"

namespace orbit {
namespace {

// A selection names objects one by one; a million is far beyond any dataset and keeps a typo
// such as "1-1000000000" (or many ranges together) from exhausting memory.
constexpr int kMaxRangeSpan = 1'000'000;

std::string_view Trim(std::string_view text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(" \t");
  return text.substr(first, last - first + 1);
}

int ParsePositive(std::string_view digits, std::string_view item) {
  int value = 0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (digits.empty() || error == std::errc::invalid_argument ||
      end != digits.data() + digits.size()) {
    throw std::invalid_argument("object selection: \"" + std::string(item) +
                                "\" is not a number or a range a-b");
  }
  if (error == std::errc::result_out_of_range) {
    throw std::invalid_argument("object selection: \"" + std::string(item) + "\" is too large");
  }
  if (value < 1) {
    throw std::invalid_argument("object selection: objects are numbered from 1, got \"" +
                                std::string(item) + "\"");
  }
  return value;
}

// Splits one CSV record into fields (RFC 4180 quoting, no embedded line breaks).
// Returns false when a quote is left open or text follows a closing quote.
bool SplitCsvRecord(std::string_view line, std::vector<std::string>& fields) {
  fields.clear();
  std::size_t i = 0;
  while (true) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    std::string field;
    if (i < line.size() && line[i] == '"') {
      ++i;
      bool closed = false;
      while (i < line.size()) {
        if (line[i] == '"') {
          if (i + 1 < line.size() && line[i + 1] == '"') {
            field += '"';
            i += 2;
          } else {
            ++i;
            closed = true;
            break;
          }
        } else {
          field += line[i++];
        }
      }
      if (!closed) return false;
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
      if (i < line.size() && line[i] != ',') return false;
    } else {
      const std::size_t comma = std::min(line.find(',', i), line.size());
      field = std::string(Trim(line.substr(i, comma - i)));
      i = comma;
    }
    fields.push_back(std::move(field));
    if (i >= line.size()) return true;
    ++i;  // the comma
  }
}

std::optional<double> ParseFiniteNumber(const std::string& text) {
  double value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size() ||
      !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

// The images of the objects numbered `numbers` (sorted ascending; objects numbered 1, 2, ... in
// order of first appearance), or with keep == false those of every other object; images keep
// their order. Throws std::invalid_argument when keep is true and a number exceeds the objects.
std::vector<DatasetImage> SelectByNumber(const std::vector<DatasetImage>& images,
                                         const std::vector<int>& numbers, bool keep) {
  const std::vector<DatasetObject> objects = GroupByObject(images);
  const int object_count = static_cast<int>(objects.size());
  if (keep && !numbers.empty() && numbers.back() > object_count) {
    throw std::invalid_argument("object " + std::to_string(numbers.back()) +
                                " selected, but the manifest has " + std::to_string(object_count) +
                                " objects");
  }
  std::vector<bool> listed(images.size(), false);
  for (int number : numbers) {
    if (number > object_count) continue;
    for (std::size_t i : objects[number - 1].images) listed[i] = true;
  }
  std::vector<DatasetImage> selected;
  for (std::size_t i = 0; i < images.size(); ++i) {
    if (listed[i] == keep) selected.push_back(images[i]);
  }
  return selected;
}

std::optional<std::vector<int>> ParseOptionalRange(const std::string& text) {
  if (text.empty()) return std::nullopt;
  return ParseObjectRange(text);
}

}  // namespace

std::vector<int> ParseObjectRange(std::string_view text) {
  if (Trim(text).empty()) throw std::invalid_argument("object selection is empty");
  std::vector<std::pair<int, int>> ranges;  // [first, last] of each item, as given
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string_view item = Trim(text.substr(start, comma - start));
    if (item.empty()) {
      throw std::invalid_argument("object selection \"" + std::string(text) +
                                  "\" has an empty item");
    }
    const std::size_t dash = item.find('-');
    if (dash == std::string_view::npos) {
      const int number = ParsePositive(item, item);
      ranges.emplace_back(number, number);
    } else {
      const int first = ParsePositive(Trim(item.substr(0, dash)), item);
      const int last = ParsePositive(Trim(item.substr(dash + 1)), item);
      if (first > last) {
        throw std::invalid_argument("object selection: range \"" + std::string(item) +
                                    "\" ends before it starts");
      }
      if (last - first >= kMaxRangeSpan) {
        throw std::invalid_argument("object selection: range \"" + std::string(item) +
                                    "\" is too large");
      }
      ranges.emplace_back(first, last);
    }
    start = comma + 1;
  }
  // The ranges in order, overlaps merged, each number written once. Nothing here computes
  // last + 1, which overflows for a range ending at the largest int.
  std::sort(ranges.begin(), ranges.end());
  std::vector<int> selected;
  for (const auto& [first, last] : ranges) {
    if (!selected.empty() && selected.back() >= last) continue;
    int n = selected.empty() ? first : std::max(first, selected.back() + 1);
    if (selected.size() + static_cast<std::size_t>(last - n) >=
        static_cast<std::size_t>(kMaxRangeSpan)) {
      throw std::invalid_argument("object selection \"" + std::string(text) +
                                  "\" selects more than a million objects");
    }
    for (;; ++n) {
      selected.push_back(n);
      if (n == last) break;
    }
  }
  return selected;
}

std::vector<DatasetImage> ListCoil100(const std::filesystem::path& dir,
                                      const std::optional<std::vector<int>>& objects) {
  std::error_code error;
  if (!std::filesystem::is_directory(dir, error)) {
    throw std::runtime_error(dir.string() + ": not a directory");
  }
  static const std::regex kName(R"(obj([0-9]+)__([0-9]+)\.png)");
  // (object number, azimuth) -> path; the key order is the listing order.
  std::map<std::tuple<long, long>, std::filesystem::path> found;
  std::filesystem::directory_iterator it(dir, error);
  if (error) throw std::runtime_error(dir.string() + ": cannot list: " + error.message());
  for (const auto& entry : it) {
    const std::string name = entry.path().filename().string();
    std::smatch match;
    if (!std::regex_match(name, match, kName) || match[1].length() > 9 || match[2].length() > 9) {
      continue;
    }
    const long object = std::stol(match[1].str());
    const long azimuth = std::stol(match[2].str());
    if (object < 1) continue;
    if (objects && !std::binary_search(objects->begin(), objects->end(), object)) continue;
    found.emplace(std::make_tuple(object, azimuth), entry.path());
  }
  if (found.empty() && !objects) {
    throw std::runtime_error(dir.string() + ": no COIL-100 images (objN__A.png) found");
  }
  if (objects) {
    for (int object : *objects) {
      const auto first = found.lower_bound(std::make_tuple(long{object}, 0L));
      if (first == found.end() || std::get<0>(first->first) != object) {
        throw std::runtime_error(dir.string() + ": no image of object " + std::to_string(object) +
                                 " (obj" + std::to_string(object) + "__A.png)");
      }
    }
  }
  std::vector<DatasetImage> images;
  images.reserve(found.size());
  for (const auto& [key, path] : found) {
    images.push_back({path.string(), "obj" + std::to_string(std::get<0>(key)),
                      NormaliseAzimuth(static_cast<double>(std::get<1>(key))), std::nullopt});
  }
  return images;
}

namespace {

// A CSV file with a header row, as the manifest and the query captures are written: its rows
// as field maps keyed by column name, with their line numbers. `columns` lists every column
// allowed, the first `required` of them required; `form` is how messages spell the header
// (e.g. "path,object,azimuth[,elevation]"), `naming` the same in words. Throws std::runtime_error
// "FILE:LINE: problem" as ReadManifest documents.
struct CsvRow {
  int line = 0;
  std::map<std::string, std::string> field;  // only the columns the header has
};

std::vector<CsvRow> ReadCsvTable(const std::filesystem::path& csv,
                                 const std::vector<std::string>& columns, std::size_t required,
                                 const std::string& form, const std::string& naming,
                                 const std::string& what) {
  std::ifstream in(csv);
  if (!in) throw std::runtime_error(csv.string() + ": cannot read the " + what);
  const auto fail = [&csv](int line, const std::string& problem) {
    return std::runtime_error(csv.string() + ":" + std::to_string(line) + ": " + problem);
  };
  std::vector<CsvRow> rows;
  std::vector<std::string> fields, header;
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (Trim(line).empty()) continue;
    if (!SplitCsvRecord(line, fields)) throw fail(line_number, "malformed quotes");
    if (header.empty()) {
      for (const std::string& name : fields) {
        if (std::find(columns.begin(), columns.end(), name) == columns.end()) {
          throw fail(line_number,
                     "unknown column \"" + name + "\" (the header must name " + naming + ")");
        }
        if (std::find(header.begin(), header.end(), name) != header.end()) {
          throw fail(line_number, "column \"" + name + "\" appears twice");
        }
        header.push_back(name);
      }
      for (std::size_t c = 0; c < required; ++c) {
        if (std::find(header.begin(), header.end(), columns[c]) == header.end()) {
          throw fail(line_number,
                     "header lacks the column \"" + columns[c] + "\" (expected " + form + ")");
        }
      }
      continue;
    }
    if (fields.size() != header.size()) {
      throw fail(line_number, "expected " + std::to_string(header.size()) + " fields, found " +
                                  std::to_string(fields.size()));
    }
    CsvRow& row = rows.emplace_back();
    row.line = line_number;
    for (std::size_t i = 0; i < header.size(); ++i) row.field[header[i]] = fields[i];
  }
  if (header.empty()) throw fail(1, "no header row (expected " + form + ")");
  return rows;
}

// The row's path, resolved against the folder of the CSV file when relative.
std::string RowPath(const CsvRow& row, const std::filesystem::path& csv) {
  const std::string& path = row.field.at("path");
  if (path.empty()) {
    throw std::runtime_error(csv.string() + ":" + std::to_string(row.line) + ": empty path");
  }
  const std::filesystem::path file(path);
  return (file.is_relative() ? csv.parent_path() / file : file).string();
}

// The row's `column` as a finite number; nullopt when the column is absent or the field empty
// and `optional`. Throws "FILE:LINE: <column> "x" is not a finite number".
std::optional<double> RowNumber(const CsvRow& row, const std::filesystem::path& csv,
                                const std::string& column, bool optional) {
  const auto found = row.field.find(column);
  if (optional && (found == row.field.end() || found->second.empty())) return std::nullopt;
  const std::string text = found == row.field.end() ? "" : found->second;
  const std::optional<double> value = ParseFiniteNumber(text);
  if (!value) {
    throw std::runtime_error(csv.string() + ":" + std::to_string(row.line) + ": " + column + " \"" +
                             text + "\" is not a finite number");
  }
  return value;
}

std::string RowObject(const CsvRow& row, const std::filesystem::path& csv) {
  const std::string& object = row.field.at("object");
  if (object.empty()) {
    throw std::runtime_error(csv.string() + ":" + std::to_string(row.line) + ": empty object name");
  }
  return object;
}

// The row's box from its x, y, w and h columns, named "FILE:LINE". Throws "FILE:LINE: <column>
// must be a whole number of at least N" (0 for x and y, 1 for w and h).
ImageBox RowBox(const CsvRow& row, const std::filesystem::path& csv) {
  const auto whole = [&](const std::string& column, int least) {
    const double value = *RowNumber(row, csv, column, false);
    if (value != std::floor(value) || value < least || value > 1e9) {
      throw std::runtime_error(csv.string() + ":" + std::to_string(row.line) + ": " + column +
                               " must be a whole number of at least " + std::to_string(least));
    }
    return static_cast<int>(value);
  };
  return {whole("x", 0), whole("y", 0), whole("w", 1), whole("h", 1),
          csv.string() + ":" + std::to_string(row.line)};
}

}  // namespace

std::vector<DatasetImage> ReadManifest(const std::filesystem::path& csv) {
  std::vector<DatasetImage> images;
  for (const CsvRow& row :
       ReadCsvTable(csv, {"path", "object", "azimuth", "elevation", "x", "y", "w", "h"}, 3,
                    "path,object,azimuth[,elevation][,x,y,w,h]",
                    "path,object,azimuth and optionally elevation and a box x,y,w,h", "manifest")) {
    DatasetImage image;
    image.path = RowPath(row, csv);
    image.object = RowObject(row, csv);
    image.azimuth = NormaliseAzimuth(*RowNumber(row, csv, "azimuth", false));
    image.elevation = RowNumber(row, csv, "elevation", true);
    const int box_columns = static_cast<int>(row.field.count("x") + row.field.count("y") +
                                             row.field.count("w") + row.field.count("h"));
    if (box_columns == 4) {
      image.box = RowBox(row, csv);
      image.box_margin = kDefaultBoxMargin;
    } else if (box_columns > 0) {
      throw std::runtime_error(csv.string() + ":" + std::to_string(row.line) +
                               ": a box needs the four columns x, y, w and h");
    }
    images.push_back(std::move(image));
  }
  if (images.empty()) throw std::runtime_error(csv.string() + ": no images");
  return images;
}

std::map<std::string, ImageBox> ReadBoxes(const std::filesystem::path& csv) {
  std::map<std::string, ImageBox> boxes;
  for (const CsvRow& row : ReadCsvTable(csv, {"path", "x", "y", "w", "h"}, 5, "path,x,y,w,h",
                                        "path,x,y,w,h", "boxes")) {
    const ImageBox box = RowBox(row, csv);
    if (!boxes.emplace(std::filesystem::path(RowPath(row, csv)).lexically_normal().string(), box)
             .second) {
      throw std::runtime_error(csv.string() + ":" + std::to_string(row.line) + ": path \"" +
                               row.field.at("path") + "\" has a box already");
    }
  }
  return boxes;
}

void AttachBoxes(std::vector<DatasetImage>& images, const std::map<std::string, ImageBox>& boxes,
                 double margin) {
  CheckBoxMargin(margin);
  // Paths are compared as absolute paths, so that an image given as an absolute path finds the
  // box a file gives it relative to the file's folder, and the other way round.
  const auto key = [](const std::string& path) {
    return std::filesystem::absolute(path).lexically_normal().string();
  };
  std::map<std::string, const ImageBox*> by_path;
  for (const auto& [path, box] : boxes) by_path.emplace(key(path), &box);
  for (DatasetImage& image : images) {
    const auto found = by_path.find(key(image.path));
    if (found == by_path.end()) throw std::invalid_argument("no box for " + image.path);
    if (image.box) {
      throw std::invalid_argument(found->second->origin + ": " + image.path +
                                  " has a box already (" + image.box->origin +
                                  "): give boxes in the manifest or in a boxes file, not both");
    }
    image.box = *found->second;
    image.box_margin = margin;
  }
}

void SetBoxMargin(std::vector<DatasetImage>& images, double margin) {
  CheckBoxMargin(margin);
  for (DatasetImage& image : images) {
    if (image.box) image.box_margin = margin;
  }
}

cv::Rect DescribedRegion(const DatasetImage& image, cv::Size size) {
  if (!image.box) return cv::Rect(cv::Point(0, 0), size);
  const ImageBox& box = *image.box;
  return ObjectRegion(cv::Rect(box.x, box.y, box.width, box.height), image.box_margin, size,
                      box.origin.empty() ? "the box of " + image.path : box.origin);
}

void CheckBoxes(const std::vector<DatasetImage>& images) {
  for (const DatasetImage& image : images) {
    if (image.box) DescribedRegion(image, ReadImageSize(image.path));
  }
}

cv::Mat ReadDescribedRegion(const DatasetImage& image) {
  const cv::Mat pixels = ReadImageFile(image.path);
  if (!image.box) return pixels;
  return pixels(DescribedRegion(image, pixels.size())).clone();
}

std::vector<CaptureFrame> ReadQueryCaptures(const std::filesystem::path& csv) {
  std::vector<CaptureFrame> frames;
  for (const CsvRow& row : ReadCsvTable(
           csv, {"path", "object", "sequence", "azimuth"}, 3, "path,object,sequence[,azimuth]",
           "path,object,sequence and optionally azimuth", "query captures")) {
    CaptureFrame frame;
    frame.path = RowPath(row, csv);
    frame.object = RowObject(row, csv);
    frame.sequence = row.field.at("sequence");
    if (frame.sequence.empty()) {
      throw std::runtime_error(csv.string() + ":" + std::to_string(row.line) + ": empty sequence");
    }
    frame.azimuth = RowNumber(row, csv, "azimuth", true);
    frame.origin = csv.string() + ":" + std::to_string(row.line);
    frames.push_back(std::move(frame));
  }
  if (frames.empty()) throw std::runtime_error(csv.string() + ": no frames");
  return frames;
}

std::vector<CaptureSequence> GroupCaptureSequences(const std::vector<CaptureFrame>& captures) {
  std::vector<CaptureSequence> sequences;
  std::map<std::string, std::size_t> position;  // name -> its place in `sequences`
  for (std::size_t f = 0; f < captures.size(); ++f) {
    const CaptureFrame& frame = captures[f];
    const auto [at, added] = position.emplace(frame.sequence, sequences.size());
    if (added) sequences.push_back({frame.sequence, frame.object, {}});
    CaptureSequence& sequence = sequences[at->second];
    if (sequence.object != frame.object) {
      throw std::invalid_argument("sequence \"" + sequence.name + "\" shows two objects (\"" +
                                  sequence.object + "\" and \"" + frame.object + "\")");
    }
    sequence.frames.push_back(f);
  }
  return sequences;
}

cv::Mat ReadCaptureImage(const CaptureFrame& frame) {
  try {
    return ReadImageFile(frame.path);
  } catch (const std::runtime_error& e) {
    if (frame.origin.empty()) throw;
    throw std::runtime_error(frame.origin + ": " + e.what());
  }
}

std::vector<DatasetImage> CaptureImages(const std::vector<CaptureFrame>& captures,
                                        const std::map<std::string, ImageBox>& boxes,
                                        double margin) {
  std::vector<DatasetImage> images(captures.size());
  for (std::size_t f = 0; f < captures.size(); ++f) {
    images[f].path = captures[f].path;
    images[f].object = captures[f].object;
  }
  if (!boxes.empty()) AttachBoxes(images, boxes, margin);
  return images;
}

std::vector<DatasetObject> GroupByObject(const std::vector<DatasetImage>& images) {
  std::vector<DatasetObject> objects;
  std::map<std::string, std::size_t> position;  // name -> its place in `objects`
  for (std::size_t i = 0; i < images.size(); ++i) {
    const auto [it, added] = position.emplace(images[i].object, objects.size());
    if (added) objects.push_back({images[i].object, {}});
    objects[it->second].images.push_back(i);
  }
  return objects;
}

namespace {

// The selection's layout: as named, or when it names none, the one of the file or folder given.
std::string LayoutOf(const DatasetSelection& selection) {
  if (!selection.layout.empty()) return selection.layout;
  if (!selection.data.empty() && !selection.manifest.empty()) {
    throw std::invalid_argument(
        "give --data DIR (a COIL-100 folder) or --manifest FILE (a CSV file), not both");
  }
  return selection.manifest.empty() ? "coil100" : "manifest";
}

}  // namespace

SelectedImages SelectDataset(const DatasetSelection& selection) {
  const std::optional<std::vector<int>> objects = ParseOptionalRange(selection.objects);
  const std::optional<std::vector<int>> unknown = ParseOptionalRange(selection.unknown_objects);
  if (objects && unknown) {
    std::vector<int> both;
    std::set_intersection(objects->begin(), objects->end(), unknown->begin(), unknown->end(),
                          std::back_inserter(both));
    if (!both.empty()) {
      throw std::invalid_argument("object " + std::to_string(both.front()) +
                                  " is in both --objects and --unknown-objects");
    }
  }
  SelectedImages selected;
  const std::string layout = LayoutOf(selection);
  if (layout == "coil100") {
    if (selection.data.empty()) {
      throw std::invalid_argument(
          selection.manifest.empty()
              ? "--layout coil100 needs --data DIR"
              : "--layout coil100 needs --data DIR; a --manifest FILE goes with --layout manifest");
    }
    selected.known = ListCoil100(selection.data, objects);
    if (unknown) {
      selected.unknown = ListCoil100(selection.data, unknown);
      std::set<std::string> names;
      for (const DatasetImage& image : selected.unknown) names.insert(image.object);
      std::erase_if(selected.known,
                    [&](const DatasetImage& image) { return names.contains(image.object); });
    }
  } else if (layout == "manifest") {
    if (selection.manifest.empty()) {
      throw std::invalid_argument("--layout manifest needs --manifest FILE");
    }
    std::vector<DatasetImage> all = ReadManifest(selection.manifest);
    if (unknown) selected.unknown = SelectByNumber(all, *unknown, true);
    if (objects) {
      selected.known = SelectByNumber(all, *objects, true);
    } else if (unknown) {
      selected.known = SelectByNumber(all, *unknown, false);
    } else {
      selected.known = std::move(all);
    }
  } else {
    throw std::invalid_argument("unknown layout \"" + selection.layout + "\"");
  }
  return selected;
}

}  // namespace orbit
