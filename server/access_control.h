// AccessControl: who may call what (docs/design.md#access-control), from the token file
// (server/token_file.h). Clients send `authorization: Bearer <token>`; the server keeps only the
// tokens' SHA-256 digests and compares a presented token's digest with every grant's in constant
// time. The file may be read again while the server runs (Reload: on SIGHUP, or when it changes):
// calls made after the reload see the new grants, and the caller learns which names lost theirs.
//
// Without a token file every caller is admitted with every right; the server then listens on
// loopback only (server/orbit_server.h enforces that).
//
// Thread-safe. Copies share the same grants (a reload is seen through every copy).
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <grpcpp/grpcpp.h>

#include "core/base/mutex.h"
#include "server/token_file.h"

namespace orbit::server {

class AuditLog;

class AccessControl {
 public:
  // Everyone may do everything.
  static AccessControl Open();

  // Grants from `file` (ReadTokenFile; throws what it throws). Its warnings are in warnings().
  static AccessControl FromFile(const std::filesystem::path& file);

  bool enabled() const { return shared_->file.has_value(); }
  std::size_t token_count() const ABSL_LOCKS_EXCLUDED(shared_->mutex);
  // The doubts of the last read of the file (server/token_file.h, TokenFile::warnings).
  std::vector<std::string> warnings() const ABSL_LOCKS_EXCLUDED(shared_->mutex);

  // Refused authentications go to `audit` from now on (it must outlive every call); none until
  // set.
  void AuditTo(AuditLog* audit) ABSL_LOCKS_EXCLUDED(shared_->mutex);

  // OK when the call's token grants `needed`; UNAUTHENTICATED when the token is missing, not a
  // Bearer token or unknown; PERMISSION_DENIED when its role is too weak (each refusal recorded
  // in the audit log under `call`, e.g. "Models/Enroll"). When OK and `token_name` is given, sets
  // it to the grant's name ("" without access control): what per-token limits and the audit log
  // count by; the token itself is never kept.
  grpc::Status Authorize(const grpc::ServerContextBase& context, Role needed, std::string_view call,
                         std::string* token_name = nullptr) const
      ABSL_LOCKS_EXCLUDED(shared_->mutex);

  // Whether the file differs (modification time, size or inode) from the one last read.
  bool FileChanged() const ABSL_LOCKS_EXCLUDED(shared_->mutex);

  // Reads the file again. On success the new grants replace the old at once, and the names
  // whose grant is gone, holds another token or a lesser role are returned (their sessions should
  // end). On a bad file, throws what ReadTokenFile throws and keeps the grants in force.
  // REQUIRES: enabled().
  std::vector<std::string> Reload() ABSL_LOCKS_EXCLUDED(shared_->mutex);

 private:
  struct FileStamp {
    std::filesystem::file_time_type modified;
    std::uintmax_t size = 0;
    std::uint64_t inode = 0;
    friend bool operator==(const FileStamp&, const FileStamp&) = default;
  };
  struct Shared {
    std::optional<std::filesystem::path> file;  // none: open to everyone
    mutable Mutex mutex;
    std::shared_ptr<const std::vector<TokenGrant>> grants ABSL_GUARDED_BY(mutex);
    std::vector<std::string> warnings ABSL_GUARDED_BY(mutex);
    FileStamp stamp ABSL_GUARDED_BY(mutex);
    AuditLog* audit ABSL_GUARDED_BY(mutex) = nullptr;
  };

  static std::optional<FileStamp> StampOf(const std::filesystem::path& file);

  std::shared_ptr<Shared> shared_ = std::make_shared<Shared>();
};

}  // namespace orbit::server
