// main() for the fuzz targets when the compiler has no libFuzzer (GCC): runs each input once
// through LLVMFuzzerTestOneInput, so that the normal build replays every seed corpus as a test.
//
//   <target>_replay PATH...   each PATH a file, or a folder whose files (not subfolders) are run
//                             in name order
//
// Prints one line per PATH with the number of inputs run; exits 0 when every input ran, 1 when a
// PATH cannot be read or holds no input (an empty corpus would replay nothing). An input that
// breaks a check aborts, as it would under libFuzzer.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <system_error>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

bool Run(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return false;
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)),
                                std::istreambuf_iterator<char>());
  if (in.bad()) return false;
  // A copy of its own, as libFuzzer gives each input: reads past its end are caught by ASan.
  std::vector<std::uint8_t> input(bytes.begin(), bytes.end());
  LLVMFuzzerTestOneInput(input.data(), input.size());
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s FILE_OR_FOLDER...\n", argv[0]);
    return 1;
  }
  for (int a = 1; a < argc; ++a) {
    const std::filesystem::path path = argv[a];
    std::vector<std::filesystem::path> files;
    std::error_code error;
    if (std::filesystem::is_directory(path, error)) {
      for (const auto& entry : std::filesystem::directory_iterator(path, error)) {
        if (entry.is_regular_file()) files.push_back(entry.path());
      }
      std::sort(files.begin(), files.end());
    } else {
      files.push_back(path);
    }
    if (error || files.empty()) {
      std::fprintf(stderr, "%s: no input to replay\n", path.c_str());
      return 1;
    }
    for (const std::filesystem::path& file : files) {
      if (!Run(file)) {
        std::fprintf(stderr, "%s: cannot read\n", file.c_str());
        return 1;
      }
    }
    std::printf("%s: %zu inputs replayed\n", path.c_str(), files.size());
  }
  return 0;
}
