#include "server/tls_credentials.h"

#include <fstream>
#include <stdexcept>
#include <string>

#include <grpcpp/security/tls_certificate_provider.h>
#include <grpcpp/security/tls_credentials_options.h>

namespace orbit::server {
namespace {

// Read once at start, so that a missing or unreadable file stops the server with its name
// (the watcher would only log its failure, later, on another thread).
void CheckReadable(const std::filesystem::path& file, const char* flag) {
  std::ifstream in(file);
  std::string first;
  if (!in || !std::getline(in, first)) {
    throw std::runtime_error(std::string(flag) + ": cannot read " + file.string());
  }
}

}  // namespace

std::shared_ptr<grpc::ServerCredentials> ServerTlsCredentials(const TlsFiles& files) {
  if (!files.cert && !files.key) {
    if (files.client_ca) throw std::runtime_error("--tls-client-ca needs --tls-cert and --tls-key");
    return grpc::InsecureServerCredentials();
  }
  if (!files.cert || !files.key)
    throw std::runtime_error("TLS needs both --tls-cert and --tls-key");
  CheckReadable(*files.cert, "--tls-cert");
  CheckReadable(*files.key, "--tls-key");
  if (files.client_ca) CheckReadable(*files.client_ca, "--tls-client-ca");
  auto provider = std::make_shared<grpc::experimental::FileWatcherCertificateProvider>(
      files.key->string(), files.cert->string(),
      files.client_ca ? files.client_ca->string() : std::string(), kCertificateRefreshSeconds);
  grpc::experimental::TlsServerCredentialsOptions options(provider);
  options.watch_identity_key_cert_pairs();
  if (files.client_ca) {
    options.watch_root_certs();
    options.set_cert_request_type(GRPC_SSL_REQUEST_AND_REQUIRE_CLIENT_CERTIFICATE_AND_VERIFY);
  } else {
    options.set_cert_request_type(GRPC_SSL_DONT_REQUEST_CLIENT_CERTIFICATE);
  }
  return grpc::experimental::TlsServerCredentials(options);
}

}  // namespace orbit::server
