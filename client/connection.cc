#include "client/connection.h"

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <grpcpp/create_channel.h>
#include <grpcpp/security/credentials.h>
#include <grpcpp/support/channel_arguments.h>

namespace orbit {
namespace {

std::string ReadFile(const std::string& path, const char* what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(std::string("cannot read ") + what + " " + path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::shared_ptr<grpc::Channel> MakeChannel(const ConnectionOptions& options) {
  grpc::ChannelArguments arguments;
  arguments.SetInt(GRPC_ARG_INITIAL_RECONNECT_BACKOFF_MS, 100);
  arguments.SetInt(GRPC_ARG_MAX_RECONNECT_BACKOFF_MS, 2000);
  // Not GRPC_ARG_MIN_RECONNECT_BACKOFF_MS: gRPC takes it as the time a connection attempt gets
  // (its minimum connect timeout, 20 s by default), not as a gap between attempts. At 100 ms a
  // handshake of a few round trips on a slow link never completed, and the first call failed
  // with UNAVAILABLE.
  if (options.own_connection) arguments.SetInt(GRPC_ARG_USE_LOCAL_SUBCHANNEL_POOL, 1);
  if (options.tls_root_certificates_file.empty()) {
    return grpc::CreateCustomChannel(options.address, grpc::InsecureChannelCredentials(),
                                     arguments);
  }
  grpc::SslCredentialsOptions ssl;
  ssl.pem_root_certs = ReadFile(options.tls_root_certificates_file, "TLS root certificate file");
  if (!options.tls_server_name.empty()) {
    arguments.SetSslTargetNameOverride(options.tls_server_name);
  }
  return grpc::CreateCustomChannel(options.address, grpc::SslCredentials(ssl), arguments);
}

}  // namespace

Connection::Connection(ConnectionOptions options) : options_(std::move(options)) {
  if (options_.address.empty()) throw std::invalid_argument("no server address (HOST:PORT)");
  channel_ = MakeChannel(options_);
}

void Connection::PrepareUnaryCall(grpc::ClientContext& context) const {
  PrepareStreamingCall(context);
  context.set_deadline(std::chrono::system_clock::now() + options_.unary_deadline);
}

void Connection::PrepareStreamingCall(grpc::ClientContext& context) const {
  if (!options_.token.empty()) context.AddMetadata("authorization", "Bearer " + options_.token);
}

bool Connection::WaitForConnected(std::chrono::milliseconds timeout) const {
  return channel_->WaitForConnected(std::chrono::system_clock::now() + timeout);
}

std::string ReadTokenFile(const std::string& path) {
  std::istringstream lines(ReadFile(path, "token file"));
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream words(line);
    std::string token;
    if (words >> token && token[0] != '#') return token;
  }
  throw std::runtime_error("no token in " + path);
}

}  // namespace orbit
