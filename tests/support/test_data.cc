#include "tests/support/test_data.h"

#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace orbit::testing {

std::filesystem::path DataDir() {
  const char* env = std::getenv("ORBIT_DATA");
  const std::filesystem::path dir =
      env != nullptr ? std::filesystem::path(env)
                     : std::filesystem::path(ORBIT_SOURCE_DIR) / ".." / "shared" / "data";
  if (!std::filesystem::is_directory(dir / "coil-100")) {
    throw std::runtime_error("shared data not found at " + dir.string() +
                             " (set ORBIT_DATA to the folder holding coil-100/)");
  }
  return dir;
}

std::vector<ReferenceVector> ReadReferenceVectors(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error("cannot read " + file.string());
  std::vector<ReferenceVector> result;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::istringstream fields(line);
    ReferenceVector ref;
    fields >> ref.path;
    ref.values = {};  // CEDD's 144 values; the rest stay 0
    for (int i = 0; i < kCeddSize; ++i) {
      std::uint8_t& v = ref.values[i];
      int value = -1;
      fields >> value;
      if (!fields || value < 0 || value > kDescriptorMaxValue) {
        throw std::runtime_error("malformed line in " + file.string() + ": " + line);
      }
      v = static_cast<std::uint8_t>(value);
    }
    result.push_back(ref);
  }
  return result;
}

namespace {
std::string Slurp(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
}  // namespace

CommandResult RunCommand(const std::string& command) {
  const auto dir = std::filesystem::temp_directory_path();
  const std::string tag = std::to_string(::getpid()) + "_" + std::to_string(std::rand());
  const auto out = dir / ("orbit_test_out_" + tag), err = dir / ("orbit_test_err_" + tag);
  const std::string full = command + " >" + out.string() + " 2>" + err.string();
  const int status = std::system(full.c_str());
  CommandResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = Slurp(out);
  result.err = Slurp(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return result;
}

ScratchDir::ScratchDir() {
  static std::atomic<int> counter{0};
  path_ = std::filesystem::temp_directory_path() /
          ("orbit_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
  std::filesystem::remove_all(path_);
  std::filesystem::create_directories(path_);
}

ScratchDir::~ScratchDir() { std::filesystem::remove_all(path_); }

std::filesystem::path ScratchDir::Write(const std::string& name, const std::string& text) const {
  const std::filesystem::path file = path_ / name;
  std::filesystem::create_directories(file.parent_path());
  std::ofstream(file) << text;
  return file;
}

std::string OrbitBinary() { return ORBIT_BINARY; }

CommandResult RunOrbit(const std::string& arguments) {
  return RunCommand(OrbitBinary() + " " + arguments);
}

std::string CoilDir() { return (DataDir() / "coil-100").string(); }

std::vector<std::string> OutputLines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> UnindentedLines(const std::string& text) {
  std::vector<std::string> lines = OutputLines(text);
  std::erase_if(lines, [](const std::string& line) { return line.starts_with(' '); });
  return lines;
}

}  // namespace orbit::testing
