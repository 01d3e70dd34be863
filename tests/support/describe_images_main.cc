// orbit_describe_images: every descriptor variant of every PNG or JPEG image under the given
// folders, one line each, "<path relative to its folder> <variant> <values as digits 0-7>",
// sorted by path. Two builds that print the same lines describe those images bit-identically
// (docs/design.md#exactness): scripts/cross.sh compares this machine's build with an ARM build
// run under emulation. --portable takes the hot loops' portable path instead of this CPU's
// fastest (core/base/cpu_dispatch.h).
//
//   orbit_describe_images [--portable] FOLDER...
//
// Exit status: 0 done, 1 an image could not be read or described (the reason on stderr),
// 2 bad usage.
#include <algorithm>
#include <exception>
#include <filesystem>
#include <iostream>
#include <string>
#include <string_view>
#include <vector>

#include "client/image_file.h"
#include "core/base/cpu_dispatch.h"
#include "core/descriptor/cedd.h"

namespace {

bool IsImage(const std::filesystem::path& path) {
  const std::string extension = path.extension().string();
  return extension == ".png" || extension == ".jpg" || extension == ".jpeg";
}

// The images under `folder`, relative to it, sorted.
std::vector<std::filesystem::path> ImagesUnder(const std::filesystem::path& folder) {
  std::vector<std::filesystem::path> images;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(folder)) {
    if (entry.is_regular_file() && IsImage(entry.path())) {
      images.push_back(std::filesystem::relative(entry.path(), folder));
    }
  }
  std::sort(images.begin(), images.end());
  return images;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::filesystem::path> folders;
  bool portable = false;
  for (int i = 1; i < argc; ++i) {
    const std::string_view argument = argv[i];
    if (argument == "--portable") {
      portable = true;
    } else if (!argument.empty() && argument.front() != '-' &&
               std::filesystem::is_directory(argv[i])) {
      folders.emplace_back(argv[i]);
    } else {
      std::cerr << "orbit_describe_images: " << argument << " is not a folder\n";
      folders.clear();
      break;
    }
  }
  if (folders.empty()) {
    std::cerr << "usage: " << argv[0] << " [--portable] FOLDER...\n";
    return 2;
  }
  if (portable) orbit::TEST_SetHotLoopPath(orbit::HotLoopPath::kPortable);
  std::string path;
  try {
    for (const std::filesystem::path& folder : folders) {
      for (const std::filesystem::path& image_path : ImagesUnder(folder)) {
        path = (folder / image_path).string();
        const cv::Mat image = orbit::ReadImageFile(path);
        for (const orbit::DescriptorVariant variant : orbit::kDescriptorVariants) {
          std::string line = image_path.string();
          line += ' ';
          line += orbit::VariantName(variant);
          line += ' ';
          const orbit::Descriptor descriptor = orbit::ExtractCedd(image, variant);
          for (int i = 0; i < orbit::DescriptorLength(variant); ++i) {
            line += static_cast<char>('0' + descriptor.values[i]);
          }
          std::cout << line << '\n';
        }
      }
    }
  } catch (const std::exception& e) {
    std::cerr << "orbit_describe_images: " << path << ": " << e.what() << "\n";
    return 1;
  }
  return 0;
}
