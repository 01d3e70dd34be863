#include "storage/store_files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>

#include "storage/schema.h"
#include "storage/sqlite_connection.h"
#include "storage/store_error.h"

namespace orbit {

bool CreateStoreFile(const std::filesystem::path& file, std::filesystem::perms mode) {
  const auto bits = static_cast<mode_t>(mode & std::filesystem::perms::mask);
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, bits);
  if (fd < 0) {
    if (errno == EEXIST) return false;
    throw StoreError(StoreError::Code::kIo,
                     "cannot create " + file.string() + ": " + std::strerror(errno));
  }
  // open() applied the umask; the mode asked for is the mode wanted (a backup keeps its source's).
  const int changed = ::fchmod(fd, bits);
  const int error = errno;
  ::close(fd);
  if (changed != 0) {
    std::error_code ignored;
    std::filesystem::remove(file, ignored);
    throw StoreError(StoreError::Code::kIo,
                     "cannot set the mode of " + file.string() + ": " + std::strerror(error));
  }
  return true;
}

bool HoldsOnlyAStore(const std::filesystem::path& file) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(file, error)) return false;
  if (std::filesystem::file_size(file, error) == 0 && !error) return true;
  try {
    SqliteConnection connection(file, SqliteConnection::Mode::kReadOnly,
                                std::chrono::milliseconds(1000));
    return ReadSchemaVersion(connection) > 0;
  } catch (const StoreError&) {
    return false;  // not a database, or a database of something else
  }
}

}  // namespace orbit
