// The model store's files on disk: who may read them, and what a copy may replace.
//
// A store holds what its operator enrolled (names, metadata and thumbnails of their objects), so
// a store this program creates, with its write-ahead log and shared-memory index, is readable and
// writable by its owner only, whatever the umask; a backup takes its source's mode, so a private
// store never leaves a readable copy behind (docs/design.md#file-safety).
#pragma once

#include <filesystem>

namespace orbit {

// The mode of a store this program creates: owner read and write, nothing for anyone else.
inline constexpr std::filesystem::perms kStoreFileMode =
    std::filesystem::perms::owner_read | std::filesystem::perms::owner_write;

// Creates `file` empty with exactly `mode` (the umask does not narrow it). Returns false, changing
// nothing, when `file` already exists. Throws StoreError kIo, naming the file, when it cannot be
// created (no such folder, no permission).
bool CreateStoreFile(const std::filesystem::path& file, std::filesystem::perms mode);

// Whether a copy of a store may replace `file` without losing anything that is not a store's:
// true when `file` is an Orbit model store (an earlier backup, say) or an empty file, false for
// anything else (another database, a document, a folder). Never throws; a file that cannot be
// read is not known to be a store, hence false.
bool HoldsOnlyAStore(const std::filesystem::path& file);

}  // namespace orbit
