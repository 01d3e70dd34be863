// WriteStoreCopy: how a copy of a model store comes to exist under a name (ModelStore::Backup),
// whichever store it copies: as one SQLite model store file.
//
// The copy is written into DESTINATION.partial, created with the mode asked for
// (storage/store_files.h), made one self-contained file (its write-ahead log folded in), checked
// with PRAGMA quick_check, then renamed over `destination` and the rename synced: `destination`
// is always either what it was or a complete, checked copy, and a crash mid-copy leaves no
// truncated file under its name (docs/design.md#file-safety).
#pragma once

#include <filesystem>
#include <functional>
#include <string>

namespace orbit {

// Creates DESTINATION.partial empty with `mode` (a leftover one is removed first), has `write`
// fill it with a model store, then checks it and renames it over `destination`. Throws
// StoreError "cannot back up SOURCE to DESTINATION: ..." with the code of what failed (kIo for
// the files, kCorrupt when the copy fails its check, or what `write` threw), having removed the
// partial file; `destination` is then unchanged.
void WriteStoreCopy(const std::string& source, const std::filesystem::path& destination,
                    std::filesystem::perms mode,
                    const std::function<void(const std::filesystem::path& partial)>& write);

}  // namespace orbit
