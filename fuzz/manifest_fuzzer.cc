// Fuzz target: a dataset manifest (evaluation/dataset.h, ReadManifest: the CSV file
// `orbit import` and `orbit eval` read with --layout manifest), the same text read as query
// captures (ReadQueryCaptures: `orbit eval --queries`), and the object selection of both
// commands (SelectDataset, with --objects and --unknown-objects parsed by ParseObjectRange).
//
// Input: "OBJECTS\0UNKNOWN\0CSV" (the two selections, then the manifest's text), or the
// manifest's text alone (no selection) when the input holds fewer than two NUL bytes. The
// manifest is written to a file in a scratch folder, as the commands read it from a file.
//
// Checked beyond "no crash": only the documented exceptions are thrown; a manifest read holds at
// least one image, each with a path, an object name, an azimuth in [0, 360) and a finite
// elevation when it has one; captures read hold at least one frame, each with a path, an
// object, a sequence and a finite azimuth when it has one; GroupByObject puts each image in
// exactly one object; and a
// selection's known and unknown images are images of the manifest in its order, of disjoint
// objects.
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "evaluation/dataset.h"
#include "fuzz/fuzz_check.h"

namespace {

// A scratch folder of this process, removed at exit.
const std::filesystem::path& ScratchFolder() {
  static const std::filesystem::path folder = [] {
    std::string pattern =
        (std::filesystem::temp_directory_path() / "orbit-manifest-fuzz-XXXXXX").string();
    ORBIT_FUZZ_CHECK(mkdtemp(pattern.data()) != nullptr);
    std::atexit([] { std::filesystem::remove_all(ScratchFolder()); });
    return std::filesystem::path(pattern);
  }();
  return folder;
}

// Whether `part` is `all` with some images left out, the others in their order.
bool IsSubsequence(const std::vector<orbit::DatasetImage>& part,
                   const std::vector<orbit::DatasetImage>& all) {
  std::size_t next = 0;
  for (const orbit::DatasetImage& image : part) {
    while (next < all.size() && !(all[next] == image)) ++next;
    if (next == all.size()) return false;
    ++next;
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace orbit;
  std::string_view input(reinterpret_cast<const char*>(data), size);
  std::string objects, unknown;
  if (const auto first = input.find('\0'); first != std::string_view::npos) {
    if (const auto second = input.find('\0', first + 1); second != std::string_view::npos) {
      objects = input.substr(0, first);
      unknown = input.substr(first + 1, second - first - 1);
      input.remove_prefix(second + 1);
    }
  }
  const std::filesystem::path csv = ScratchFolder() / "manifest.csv";
  {
    std::ofstream out(csv, std::ios::binary | std::ios::trunc);
    out.write(input.data(), static_cast<std::streamsize>(input.size()));
  }

  try {
    const std::vector<CaptureFrame> frames = ReadQueryCaptures(csv);
    ORBIT_FUZZ_CHECK(!frames.empty());
    for (const CaptureFrame& frame : frames) {
      ORBIT_FUZZ_CHECK(!frame.path.empty() && !frame.object.empty() && !frame.sequence.empty());
      ORBIT_FUZZ_CHECK(!frame.azimuth || std::isfinite(*frame.azimuth));
    }
  } catch (const std::runtime_error&) {
  }

  std::vector<DatasetImage> all;
  try {
    all = ReadManifest(csv);
  } catch (const std::runtime_error&) {
    return 0;
  }
  ORBIT_FUZZ_CHECK(!all.empty());
  for (const DatasetImage& image : all) {
    ORBIT_FUZZ_CHECK(!image.path.empty() && !image.object.empty());
    ORBIT_FUZZ_CHECK(image.azimuth >= 0 && image.azimuth < 360);
    ORBIT_FUZZ_CHECK(!image.elevation || std::isfinite(*image.elevation));
  }
  std::size_t grouped = 0;
  std::set<std::string> names;
  for (const DatasetObject& object : GroupByObject(all)) {
    ORBIT_FUZZ_CHECK(names.insert(object.name).second);
    for (std::size_t i : object.images) ORBIT_FUZZ_CHECK(all.at(i).object == object.name);
    grouped += object.images.size();
  }
  ORBIT_FUZZ_CHECK(grouped == all.size());

  SelectedImages selected;
  try {
    selected = SelectDataset({"manifest", "", csv, objects, unknown});
  } catch (const std::invalid_argument&) {
    return 0;
  } catch (const std::runtime_error&) {
    ORBIT_FUZZ_CHECK(false);  // the manifest was read above: only the selection can be refused
  }
  ORBIT_FUZZ_CHECK(IsSubsequence(selected.known, all));
  ORBIT_FUZZ_CHECK(IsSubsequence(selected.unknown, all));
  std::set<std::string> unknown_names;
  for (const DatasetImage& image : selected.unknown) unknown_names.insert(image.object);
  for (const DatasetImage& image : selected.known) {
    ORBIT_FUZZ_CHECK(!unknown_names.contains(image.object));
  }
  return 0;
}
