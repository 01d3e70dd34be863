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

#include "core/angles.h"

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
  if (digits.empty() || error == std::errc::invalid_argument || end != digits.data() + digits.size()) {
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

std::vector<DatasetImage> ReadManifest(const std::filesystem::path& csv) {
  std::ifstream in(csv);
  if (!in) throw std::runtime_error(csv.string() + ": cannot read the manifest");
  const std::filesystem::path base = csv.parent_path();
  const auto fail = [&csv](int line, const std::string& problem) {
    return std::runtime_error(csv.string() + ":" + std::to_string(line) + ": " + problem);
  };

  std::vector<DatasetImage> images;
  std::vector<std::string> fields;
  std::map<std::string, std::size_t> column;  // header name -> field index
  std::size_t column_count = 0;
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (Trim(line).empty()) continue;
    if (!SplitCsvRecord(line, fields)) throw fail(line_number, "malformed quotes");
    if (column_count == 0) {  // the header
      for (std::size_t i = 0; i < fields.size(); ++i) {
        const std::string& name = fields[i];
        if (name != "path" && name != "object" && name != "azimuth" && name != "elevation") {
          throw fail(line_number, "unknown column \"" + name +
                                      "\" (the header must name path,object,azimuth and "
                                      "optionally elevation)");
        }
        if (!column.emplace(name, i).second) {
          throw fail(line_number, "column \"" + name + "\" appears twice");
        }
      }
      for (const char* required : {"path", "object", "azimuth"}) {
        if (!column.contains(required)) {
          throw fail(line_number, std::string("header lacks the column \"") + required +
                                      "\" (expected path,object,azimuth[,elevation])");
        }
      }
      column_count = fields.size();
      continue;
    }
    if (fields.size() != column_count) {
      throw fail(line_number, "expected " + std::to_string(column_count) + " fields, found " +
                                  std::to_string(fields.size()));
    }
    DatasetImage image;
    const std::string& path = fields[column.at("path")];
    if (path.empty()) throw fail(line_number, "empty path");
    const std::filesystem::path file(path);
    image.path = (file.is_relative() ? base / file : file).string();
    image.object = fields[column.at("object")];
    if (image.object.empty()) throw fail(line_number, "empty object name");
    const std::string& azimuth = fields[column.at("azimuth")];
    const std::optional<double> degrees = ParseFiniteNumber(azimuth);
    if (!degrees) throw fail(line_number, "azimuth \"" + azimuth + "\" is not a finite number");
    image.azimuth = NormaliseAzimuth(*degrees);
    if (const auto e = column.find("elevation"); e != column.end() && !fields[e->second].empty()) {
      image.elevation = ParseFiniteNumber(fields[e->second]);
      if (!image.elevation) {
        throw fail(line_number, "elevation \"" + fields[e->second] + "\" is not a finite number");
      }
    }
    images.push_back(std::move(image));
  }
  if (column_count == 0) throw fail(1, "no header row (expected path,object,azimuth[,elevation])");
  if (images.empty()) throw std::runtime_error(csv.string() + ": no images");
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
  if (selection.layout == "coil100") {
    if (selection.data.empty()) throw std::invalid_argument("--layout coil100 needs --data DIR");
    selected.known = ListCoil100(selection.data, objects);
    if (unknown) {
      selected.unknown = ListCoil100(selection.data, unknown);
      std::set<std::string> names;
      for (const DatasetImage& image : selected.unknown) names.insert(image.object);
      std::erase_if(selected.known,
                    [&](const DatasetImage& image) { return names.contains(image.object); });
    }
  } else if (selection.layout == "manifest") {
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
