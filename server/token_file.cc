#include "server/token_file.h"

#include <sys/stat.h>

#include <openssl/rand.h>
#include <openssl/sha.h>

#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

namespace orbit::server {
namespace {

constexpr std::size_t kMinTokenLength = 16;
constexpr std::size_t kMaxNameLength = 64;

}  // namespace

bool IsTokenName(std::string_view name) {
  if (name.empty() || name.size() > kMaxNameLength) return false;
  for (const char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '-' || c == '.';
    if (!ok) return false;
  }
  return true;
}

namespace {

bool ParseRole(std::string_view text, Role* role) {
  if (text == "recognize") {
    *role = Role::kRecognize;
  } else if (text == "admin") {
    *role = Role::kAdmin;
  } else {
    return false;
  }
  return true;
}

bool ParseDigest(std::string_view hex, TokenDigest* out) {
  if (hex.size() != 64) return false;
  for (std::size_t i = 0; i < 32; ++i) {
    int byte = 0;
    for (int half = 0; half < 2; ++half) {
      const char c = hex[2 * i + half];
      int value;
      if (c >= '0' && c <= '9') {
        value = c - '0';
      } else if (c >= 'a' && c <= 'f') {
        value = c - 'a' + 10;
      } else if (c >= 'A' && c <= 'F') {
        value = c - 'A' + 10;
      } else {
        return false;
      }
      byte = byte * 16 + value;
    }
    (*out)[i] = static_cast<std::uint8_t>(byte);
  }
  return true;
}

// Refuses a file other users may read, or anyone but its owner may write: the tokens (even as
// digests, which name the callers) are the server's secrets.
void CheckPermissions(const std::filesystem::path& file) {
  struct stat info {};
  if (stat(file.c_str(), &info) != 0) return;  // the read below reports it
  const mode_t mode = info.st_mode & 0777;
  if ((mode & (S_IRWXO | S_IWGRP)) != 0) {
    std::ostringstream octal;
    octal << std::oct << mode;
    throw std::runtime_error(file.string() + ": other users may " +
                             ((mode & S_IROTH) != 0 ? "read" : "write") +
                             " the token file (mode 0" + octal.str() +
                             "); make it the server's alone: chmod 600 " + file.string());
  }
}

}  // namespace

TokenFile ReadTokenFile(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file.string() + ": cannot read the token file");
  CheckPermissions(file);
  TokenFile result;
  std::set<std::string> names;
  std::set<TokenDigest> digests;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::string where = file.string() + ":" + std::to_string(number) + ": ";
    std::istringstream fields(line);
    std::vector<std::string> field;
    for (std::string f; fields >> f;) field.push_back(f);
    if (field.empty()) continue;
    Role role;
    if (field[0][0] == '#') {
      if (field.size() == 2 && field[0].size() >= kMinTokenLength && ParseRole(field[1], &role)) {
        result.warnings.push_back(where +
                                  "read as a comment, though it looks like a token and a role: "
                                  "a token may not start with '#'");
      }
      continue;
    }
    if (field.size() < 2 || field.size() > 3) {
      throw std::runtime_error(where + "expected `<name> <role> <sha256>` (or `<token> <role>`)");
    }
    if (!ParseRole(field[1], &role)) {
      throw std::runtime_error(where + "unknown role '" + field[1] + "' (recognize or admin)");
    }
    TokenGrant grant;
    grant.role = role;
    if (field.size() == 3) {
      if (!IsTokenName(field[0])) {
        throw std::runtime_error(where + "name '" + field[0] +
                                 "' is not 1..64 letters, digits, '_', '-' or '.'");
      }
      grant.certificate = field[2] == "certificate";
      if (!grant.certificate && !ParseDigest(field[2], &grant.digest)) {
        throw std::runtime_error(where +
                                 "expected the token's SHA-256 as 64 hex digits, or `certificate`");
      }
      grant.name = field[0];
    } else {
      if (field[0].size() < kMinTokenLength) {
        throw std::runtime_error(where + "token shorter than " + std::to_string(kMinTokenLength) +
                                 " characters");
      }
      grant.digest = DigestOf(field[0]);
      grant.name = "token-" + HexOf(grant.digest).substr(0, 8);
      result.warnings.push_back(where + "a token in clear text (named " + grant.name + "): give `" +
                                TokenFileLine(grant.name, role, field[0]) +
                                "` instead, which holds only its SHA-256");
    }
    if (!grant.certificate && !digests.insert(grant.digest).second) {
      throw std::runtime_error(where + "duplicate token");
    }
    if (!names.insert(grant.name).second) {
      throw std::runtime_error(where + "duplicate name '" + grant.name + "'");
    }
    result.grants.push_back(std::move(grant));
  }
  if (result.grants.empty()) throw std::runtime_error(file.string() + ": no tokens in the file");
  return result;
}

TokenDigest DigestOf(std::string_view token) {
  TokenDigest digest;
  SHA256(reinterpret_cast<const unsigned char*>(token.data()), token.size(), digest.data());
  return digest;
}

std::string HexOf(const TokenDigest& digest) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string hex;
  for (const std::uint8_t byte : digest) {
    hex += kHex[byte >> 4];
    hex += kHex[byte & 15];
  }
  return hex;
}

std::string NewToken() {
  unsigned char bytes[32];
  if (RAND_bytes(bytes, sizeof bytes) != 1) {
    throw std::runtime_error("the system's random generator failed");
  }
  static constexpr char kBase64Url[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-_";
  std::string token;
  std::uint32_t bits = 0;
  int held = 0;
  for (const unsigned char byte : bytes) {
    bits = (bits << 8) | byte;
    held += 8;
    while (held >= 6) {
      held -= 6;
      token += kBase64Url[(bits >> held) & 63];
    }
  }
  if (held > 0) token += kBase64Url[(bits << (6 - held)) & 63];
  return token;
}

std::string TokenFileLine(std::string_view name, Role role, std::string_view token) {
  return std::string(name) + " " + std::string(RoleName(role)) + " " + HexOf(DigestOf(token));
}

std::string_view RoleName(Role role) { return role == Role::kAdmin ? "admin" : "recognize"; }

}  // namespace orbit::server
