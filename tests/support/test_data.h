// Where the tests find the shared data and the orbit binary.
#pragma once

#include <array>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/descriptor/descriptor.h"

namespace orbit::testing {

// The shared data folder: $ORBIT_DATA if set, else ../shared/data beside the repository.
// Fails the calling test (fatally, never a skip) when the folder is missing.
std::filesystem::path DataDir();

// One line of a LIRE reference file: `<relative path> v0 ... v143`.
struct ReferenceVector {
  std::string path;
  DescriptorValues values;
};
std::vector<ReferenceVector> ReadReferenceVectors(const std::filesystem::path& file);

// A fresh folder under the system's temp dir, removed with everything in it at the end.
class ScratchDir {
 public:
  ScratchDir();
  ~ScratchDir();
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

  // Writes `text` to the file `name` in the folder (creating subfolders); returns its path.
  std::filesystem::path Write(const std::string& name, const std::string& text) const;

 private:
  std::filesystem::path path_;
};

// Runs a command through the shell; returns its exit status and what it printed.
struct CommandResult {
  int exit_code = -1;
  std::string out;  // stdout
  std::string err;  // stderr
};
CommandResult RunCommand(const std::string& command);

// Path of the `orbit` binary the tests run: the build's own, or in a device-only build the one
// named by ORBIT_TEST_SERVER (tests/CMakeLists.txt).
std::string OrbitBinary();

// RunCommand of `orbit ARGUMENTS`.
CommandResult RunOrbit(const std::string& arguments);

// The COIL-100 folder of the shared data.
std::string CoilDir();

// The message of the `Error` that `call` throws; "" (and a test failure) when it throws none.
template <typename Error = std::invalid_argument, typename Call>
std::string ErrorMessageOf(Call call) {
  try {
    call();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no exception thrown";
  return "";
}

// The lines of a command's output, without their "\n".
std::vector<std::string> OutputLines(const std::string& text);
// The lines of `text` that do not start with a space: `orbit enroll` and `orbit import` print
// each object's enrollment report indented under its line.
std::vector<std::string> UnindentedLines(const std::string& text);

}  // namespace orbit::testing
