#include "server/access_control.h"

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace orbit::server {
namespace {

constexpr std::size_t kMinTokenLength = 16;

}  // namespace

AccessControl AccessControl::Open() { return AccessControl(); }

AccessControl AccessControl::FromFile(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file.string() + ": cannot read the token file");
  AccessControl access;
  access.enabled_ = true;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::string where = file.string() + ":" + std::to_string(number) + ": ";
    std::istringstream fields(line);
    std::string token, role, extra;
    if (!(fields >> token) || token[0] == '#') continue;
    if (!(fields >> role) || (fields >> extra)) {
      throw std::runtime_error(where + "expected `<token> <role>`");
    }
    if (token.size() < kMinTokenLength) {
      throw std::runtime_error(where + "token shorter than " + std::to_string(kMinTokenLength) +
                               " characters");
    }
    Role parsed;
    if (role == "recognize") {
      parsed = Role::kRecognize;
    } else if (role == "admin") {
      parsed = Role::kAdmin;
    } else {
      throw std::runtime_error(where + "unknown role '" + role + "' (recognize or admin)");
    }
    if (!access.roles_.emplace(token, Grant{parsed, "line " + std::to_string(number)}).second) {
      throw std::runtime_error(where + "duplicate token");
    }
  }
  if (access.roles_.empty()) throw std::runtime_error(file.string() + ": no tokens in the file");
  return access;
}

grpc::Status AccessControl::Authorize(const grpc::ServerContextBase& context, Role needed,
                                      std::string* token_name) const {
  if (token_name != nullptr) token_name->clear();
  if (!enabled_) return grpc::Status::OK;
  const auto& metadata = context.client_metadata();
  const auto header = metadata.find("authorization");
  if (header == metadata.end()) {
    return {grpc::StatusCode::UNAUTHENTICATED, "missing `authorization: Bearer <token>` metadata"};
  }
  const std::string value(header->second.data(), header->second.size());
  constexpr std::string_view kBearer = "Bearer ";
  if (value.compare(0, kBearer.size(), kBearer) != 0) {
    return {grpc::StatusCode::UNAUTHENTICATED, "authorization metadata is not `Bearer <token>`"};
  }
  const auto role = roles_.find(value.substr(kBearer.size()));
  if (role == roles_.end()) return {grpc::StatusCode::UNAUTHENTICATED, "unknown token"};
  if (needed == Role::kAdmin && role->second.role != Role::kAdmin) {
    return {grpc::StatusCode::PERMISSION_DENIED, "this call needs a token with the admin role"};
  }
  if (token_name != nullptr) *token_name = role->second.name;
  return grpc::Status::OK;
}

}  // namespace orbit::server
