// How `orbit` reports a call that failed (client/rpc_error.h): which subcommand failed, and, when
// the server could not be reached at all, where the user expected it and what to check, rather
// than gRPC's own account of its connection attempts.
#pragma once

#include <string>
#include <string_view>

#include "client/rpc_error.h"

namespace orbit::cli {

// The line to print for `error`, raised while `orbit <command>` talked to `server` (its --server
// HOST:PORT; empty when the command named none). A server that could not be reached:
// "orbit recognize: cannot reach a server at HOST:PORT (<gRPC's last reason>): is `orbit serve`
// running at HOST:PORT?". Anything else, including the UNAVAILABLE a running server sends while
// it starts or shuts down: "orbit recognize: <error.what()>", the call, code and the server's
// message unchanged.
std::string RpcErrorText(std::string_view command, std::string_view server, const RpcError& error);

}  // namespace orbit::cli
