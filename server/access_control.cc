#include "server/access_control.h"

#include <openssl/crypto.h>
#include <sys/stat.h>

#include <set>

#include <grpc/grpc_security_constants.h>

#include "server/audit_log.h"

namespace orbit::server {
namespace {

// The grant of the client certificate the connection was verified with (mutual TLS: gRPC has
// checked it against --tls-client-ca), found by its common name; nullptr without one.
const TokenGrant* CertifiedGrant(const grpc::ServerContextBase& context,
                                 const std::vector<TokenGrant>& grants) {
  const std::shared_ptr<const grpc::AuthContext> auth = context.auth_context();
  if (auth == nullptr || !auth->IsPeerAuthenticated()) return nullptr;
  for (const grpc::string_ref& name : auth->FindPropertyValues(GRPC_X509_CN_PROPERTY_NAME)) {
    for (const TokenGrant& grant : grants) {
      if (grant.certificate && grant.name == std::string_view(name.data(), name.size())) {
        return &grant;
      }
    }
  }
  return nullptr;
}

}  // namespace

AccessControl AccessControl::Open() { return AccessControl(); }

AccessControl AccessControl::FromFile(const std::filesystem::path& file) {
  AccessControl access;
  access.shared_->file = file;
  TokenFile read = ReadTokenFile(file);
  MutexLock lock(&access.shared_->mutex);
  access.shared_->grants = std::make_shared<const std::vector<TokenGrant>>(std::move(read.grants));
  access.shared_->warnings = std::move(read.warnings);
  access.shared_->stamp = StampOf(file).value_or(FileStamp{});
  return access;
}

std::size_t AccessControl::token_count() const {
  MutexLock lock(&shared_->mutex);
  return shared_->grants ? shared_->grants->size() : 0;
}

std::vector<std::string> AccessControl::warnings() const {
  MutexLock lock(&shared_->mutex);
  return shared_->warnings;
}

void AccessControl::AuditTo(AuditLog* audit) {
  MutexLock lock(&shared_->mutex);
  shared_->audit = audit;
}

grpc::Status AccessControl::Authorize(const grpc::ServerContextBase& context, Role needed,
                                      std::string_view call, std::string* token_name) const {
  if (token_name != nullptr) token_name->clear();
  if (!enabled()) return grpc::Status::OK;
  std::shared_ptr<const std::vector<TokenGrant>> grants;
  AuditLog* audit = nullptr;
  {
    MutexLock lock(&shared_->mutex);
    grants = shared_->grants;
    audit = shared_->audit;
  }
  const TokenGrant* granted = nullptr;
  grpc::Status status;
  const auto& metadata = context.client_metadata();
  const auto header = metadata.find("authorization");
  constexpr std::string_view kBearer = "Bearer ";
  if (header == metadata.end()) {
    granted = CertifiedGrant(context, *grants);
    if (granted == nullptr) {
      status = {grpc::StatusCode::UNAUTHENTICATED,
                "missing `authorization: Bearer <token>` metadata (or a client certificate "
                "the token file names)"};
    } else if (needed == Role::kAdmin && granted->role != Role::kAdmin) {
      status = {grpc::StatusCode::PERMISSION_DENIED,
                "this call needs a certificate or token with the admin role"};
    }
  } else if (const std::string_view value(header->second.data(), header->second.size());
             value.substr(0, kBearer.size()) != kBearer) {
    status = {grpc::StatusCode::UNAUTHENTICATED, "authorization metadata is not `Bearer <token>`"};
  } else {
    // Every grant is compared, each in constant time: how long this takes says nothing about
    // how close a guess came, nor which grant it resembles.
    const TokenDigest digest = DigestOf(value.substr(kBearer.size()));
    for (const TokenGrant& grant : *grants) {
      if (!grant.certificate &&
          CRYPTO_memcmp(digest.data(), grant.digest.data(), digest.size()) == 0) {
        granted = &grant;
      }
    }
    if (granted == nullptr) {
      status = {grpc::StatusCode::UNAUTHENTICATED, "unknown token"};
    } else if (needed == Role::kAdmin && granted->role != Role::kAdmin) {
      status = {grpc::StatusCode::PERMISSION_DENIED, "this call needs a token with the admin role"};
    }
  }
  if (!status.ok()) {
    if (audit != nullptr) {
      const std::string peer = context.peer();
      audit->Record({.call = call,
                     .token = granted != nullptr ? std::string_view(granted->name) : "",
                     .peer = peer,
                     .outcome = status.error_code(),
                     .message = status.error_message()});
    }
    return status;
  }
  if (token_name != nullptr) *token_name = granted->name;
  return grpc::Status::OK;
}

std::optional<AccessControl::FileStamp> AccessControl::StampOf(const std::filesystem::path& file) {
  struct stat info {};
  if (stat(file.c_str(), &info) != 0) return std::nullopt;
  std::error_code error;
  return FileStamp{std::filesystem::last_write_time(file, error),
                   static_cast<std::uintmax_t>(info.st_size),
                   static_cast<std::uint64_t>(info.st_ino)};
}

bool AccessControl::FileChanged() const {
  if (!enabled()) return false;
  const std::optional<FileStamp> now = StampOf(*shared_->file);
  MutexLock lock(&shared_->mutex);
  return now && !(*now == shared_->stamp);
}

std::vector<std::string> AccessControl::Reload() {
  const std::optional<FileStamp> stamp = StampOf(*shared_->file);
  TokenFile read = ReadTokenFile(*shared_->file);
  auto fresh = std::make_shared<const std::vector<TokenGrant>>(std::move(read.grants));
  std::vector<std::string> revoked;
  MutexLock lock(&shared_->mutex);
  for (const TokenGrant& old : *shared_->grants) {
    bool kept = false;
    for (const TokenGrant& grant : *fresh) {
      kept = kept || (grant.name == old.name && grant.digest == old.digest &&
                      grant.certificate == old.certificate &&
                      (grant.role == Role::kAdmin || old.role == Role::kRecognize));
    }
    if (!kept) revoked.push_back(old.name);
  }
  shared_->grants = std::move(fresh);
  shared_->warnings = std::move(read.warnings);
  shared_->stamp = stamp.value_or(FileStamp{});
  return revoked;
}

}  // namespace orbit::server
