#include "cli/rpc_error_text.h"

#include <array>
#include <regex>

namespace orbit::cli {
namespace {

// True when gRPC itself failed the call because no connection to the server could be made or
// kept: the texts gRPC's channel gives, as opposed to an UNAVAILABLE sent by a server that is
// running (docs/service.md, "Status codes").
bool IsUnreachable(const RpcError& error) {
  if (error.code() != grpc::StatusCode::UNAVAILABLE) return false;
  static constexpr std::array<std::string_view, 6> kChannelTexts = {
      "failed to connect to all addresses",
      "DNS resolution failed",
      "empty address list",
      "Connection refused",
      "Socket closed",
      "Connection reset"};
  const std::string& message = error.status().error_message();
  for (const std::string_view text : kChannelTexts) {
    if (message.find(text) != std::string::npos) return true;
  }
  return false;
}

// gRPC's reason, without its account of the attempt: what follows "last error: ", less the
// status code and the resolved address gRPC puts before it ("UNKNOWN: ipv4:127.0.0.1:5: "); for
// a name that did not resolve, the resolver's last words ("Domain name not found").
std::string BriefReason(const std::string& message) {
  std::string reason = message;
  static constexpr std::string_view kLast = "last error: ";
  if (const auto last = reason.rfind(kLast); last != std::string::npos) {
    reason = reason.substr(last + kLast.size());
  }
  static const std::regex kCode("^[A-Z_]+: ");
  static const std::regex kAddress("^(ipv4|ipv6|unix):\\S+: ");
  reason = std::regex_replace(reason, kCode, "", std::regex_constants::format_first_only);
  reason = std::regex_replace(reason, kAddress, "", std::regex_constants::format_first_only);
  // A name that did not resolve: the resolver's own account of its query is left out.
  static constexpr std::string_view kDns = "DNS resolution failed";
  if (reason.rfind(kDns, 0) == 0) {
    if (const auto last = reason.rfind(": "); last != std::string::npos) {
      return std::string(kDns) + ": " + reason.substr(last + 2);
    }
  }
  return reason;
}

}  // namespace

std::string RpcErrorText(std::string_view command, std::string_view server, const RpcError& error) {
  const std::string prefix = "orbit " + std::string(command) + ": ";
  if (server.empty() || !IsUnreachable(error)) return prefix + error.what();
  const std::string at(server);
  return prefix + "cannot reach a server at " + at + " (" +
         BriefReason(error.status().error_message()) + "): is `orbit serve` running at " + at + "?";
}

}  // namespace orbit::cli
