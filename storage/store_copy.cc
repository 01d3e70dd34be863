#include "storage/store_copy.h"

#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <system_error>

#include "storage/sqlite_connection.h"
#include "storage/store_error.h"
#include "storage/store_files.h"

namespace orbit {
namespace {

// How long the check of the copy waits for a lock: nothing else opens the partial file.
constexpr std::chrono::milliseconds kCopyBusyTimeout(5000);

// Makes a completed rename or file creation in `directory` durable.
void SyncDirectory(const std::filesystem::path& directory) {
  const int fd = ::open(directory.empty() ? "." : directory.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) return;  // nothing to sync on file systems without directory handles
  ::fsync(fd);
  ::close(fd);
}

// Folds the copy's write-ahead log into it (a copy of a WAL store says WAL in its header) and
// checks it before it is kept.
void SealCopy(const std::filesystem::path& partial) {
  SqliteConnection copy(partial, SqliteConnection::Mode::kReadWrite, kCopyBusyTimeout);
  copy.Execute("PRAGMA journal_mode = DELETE");
  const std::string verdict = copy.QueryText("PRAGMA quick_check");
  if (verdict != "ok") {
    throw StoreError(StoreError::Code::kCorrupt, "the copy failed quick_check: " + verdict);
  }
}

}  // namespace

void WriteStoreCopy(const std::string& source, const std::filesystem::path& destination,
                    std::filesystem::perms mode,
                    const std::function<void(const std::filesystem::path& partial)>& write) {
  const std::filesystem::path partial = destination.string() + ".partial";
  const std::string what = "cannot back up " + source + " to " + destination.string() + ": ";
  std::error_code ignored;
  std::filesystem::remove(partial, ignored);
  try {
    CreateStoreFile(partial, mode);
    write(partial);
    SealCopy(partial);
    std::filesystem::rename(partial, destination);
    SyncDirectory(destination.parent_path());
  } catch (const StoreError& e) {
    std::filesystem::remove(partial, ignored);
    throw StoreError(e.code(), what + e.what());
  } catch (const std::filesystem::filesystem_error& e) {
    std::filesystem::remove(partial, ignored);
    throw StoreError(StoreError::Code::kIo, what + e.what());
  } catch (...) {
    std::filesystem::remove(partial, ignored);
    throw;
  }
}

}  // namespace orbit
