// AccessControl: who may call what (docs/design.md#service-behaviour).
//
// Tokens come from a file, one per line: `<token> <role>`, role `recognize` (sessions and reads)
// or `admin` (everything, including enroll, add views and delete). Blank lines and lines
// starting with '#' are ignored. Clients send `authorization: Bearer <token>`.
//
// Without a token file every caller is admitted with every right; the server then listens on
// loopback only (server/orbit_server.h enforces that).
//
// Thread-safe: immutable after construction.
#pragma once

#include <filesystem>
#include <string>
#include <unordered_map>

#include <grpcpp/grpcpp.h>

namespace orbit::server {

enum class Role {
  kRecognize,  // sessions, Recognize, ListObjects, GetObject, ServerInfo
  kAdmin,      // all of the above, and Enroll, AddViews, DeleteObject
};

class AccessControl {
 public:
  // Everyone may do everything.
  static AccessControl Open();

  // Tokens from `file`. Throws std::runtime_error naming the file and line of the first problem:
  // unreadable file, a line without exactly a token and a role, an unknown role, a token
  // shorter than 16 characters, a duplicate token, or no token at all.
  static AccessControl FromFile(const std::filesystem::path& file);

  bool enabled() const { return enabled_; }
  std::size_t token_count() const { return roles_.size(); }

  // OK when the call's token grants `needed`; UNAUTHENTICATED when the token is missing, not a
  // Bearer token or unknown; PERMISSION_DENIED when its role is too weak. When OK and
  // `token_name` is given, sets it to the token's name ("" without access control), what
  // per-token limits count by: the token itself is never kept beyond this call.
  grpc::Status Authorize(const grpc::ServerContextBase& context, Role needed,
                         std::string* token_name = nullptr) const;

 private:
  struct Grant {
    Role role;
    std::string name;  // "line N" of the token file
  };
  bool enabled_ = false;
  std::unordered_map<std::string, Grant> roles_;
};

}  // namespace orbit::server
