// The server's TLS (docs/service.md, "Access control and TLS"): its certificate and key, and with
// a client CA, mutual TLS, where a client proves who it is with a certificate that CA signed.
// The files are watched: a certificate renewed on disk (a new key and chain, or a new CA) is
// served to new connections within kCertificateRefreshSeconds, without a restart or a signal.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>

#include <grpcpp/security/server_credentials.h>

namespace orbit::server {

inline constexpr unsigned kCertificateRefreshSeconds = 5;

struct TlsFiles {
  std::optional<std::filesystem::path> cert;       // PEM certificate chain
  std::optional<std::filesystem::path> key;        // PEM private key
  std::optional<std::filesystem::path> client_ca;  // PEM CA bundle: clients must show a cert
};

// Insecure credentials without cert and key; else TLS from the files, requiring and verifying a
// client certificate when client_ca is given. Throws std::runtime_error naming the flag when only
// one of cert and key is given, client_ca without them, or a file cannot be read.
std::shared_ptr<grpc::ServerCredentials> ServerTlsCredentials(const TlsFiles& files);

}  // namespace orbit::server
