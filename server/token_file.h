// The token file of `orbit serve --tokens` (docs/service.md, "Access control and TLS"): who may
// call, under which name, with which role. One grant per line:
//
//   <name> <role> <sha256>   a token known by its SHA-256 (64 hex digits), as `orbit token` prints
//                            it: the file holds nothing a reader could call with
//   <token> <role>           a token in clear text, still read, with a warning; named
//                            "token-" and the first 8 hex digits of its SHA-256
//   <name> <role> certificate  a client of mutual TLS whose certificate's common name is <name>
//                            (orbit serve --tls-client-ca: the certificate is verified first)
//
// Roles are `recognize` and `admin`. Blank lines and lines whose first field starts with '#' are
// comments. Names are 1..64 letters, digits, '_', '-' and '.'; tokens at least 16 characters.
// The file is refused when users other than its owner (and its group) may read it, or anyone but
// its owner may write it.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace orbit::server {

enum class Role {
  kRecognize,  // sessions, Recognize, ListObjects, GetObject, ServerInfo
  kAdmin,      // all of the above, and Enroll, AddViews, DeleteObject
};

using TokenDigest = std::array<std::uint8_t, 32>;  // SHA-256

struct TokenGrant {
  std::string name;
  Role role = Role::kRecognize;
  TokenDigest digest{};      // unused for a certificate's grant
  bool certificate = false;  // granted to a client certificate named `name`, not to a token
};

struct TokenFile {
  std::vector<TokenGrant> grants;
  // One per line read with a doubt (a token in clear text, a comment that looks like a token
  // line), "<file>:<line>: ..." each.
  std::vector<std::string> warnings;
};

// Reads `file`. Throws std::runtime_error naming the file, and the line when there is one, for:
// an unreadable file, permissions that let other users read it or anyone but its owner write it,
// a line that is not one of the two forms, an unknown role, a bad name or digest, a token shorter
// than 16 characters, a duplicate name or token, or no grant at all.
TokenFile ReadTokenFile(const std::filesystem::path& file);

// The SHA-256 of `token`.
TokenDigest DigestOf(std::string_view token);
std::string HexOf(const TokenDigest& digest);

// A new token: 32 random bytes from the system's generator, as 43 characters of base64url
// (letters, digits, '-' and '_'; never '#').
std::string NewToken();

// The line of the token file that grants `token` to `name` with `role`: "<name> <role> <sha256>".
std::string TokenFileLine(std::string_view name, Role role, std::string_view token);

std::string_view RoleName(Role role);

// True for 1..64 letters, digits, '_', '-' and '.': a grant's name.
bool IsTokenName(std::string_view name);

}  // namespace orbit::server
