// Connection admission: which accepted TCP connections the process keeps, decided inside
// accept4 itself (docs/design.md#connection-admission).
//
// Why here: gRPC 1.51 (Debian 12's) closes its listening socket for good when accept4 fails with
// EMFILE, so a flood of idle connections that fills the descriptor table once stops the server
// from ever accepting again. This file defines accept4 for the process: it calls the C library's,
// refuses (closes at once) a connection that would leave fewer than the reserve of descriptors
// free, and turns a full descriptor table into "nothing to accept" (EAGAIN) after taking and
// closing the waiting connections with a spare descriptor. gRPC's listener therefore never sees
// EMFILE, the descriptors the store, the logs and the metrics need stay free, and the server
// accepts again as soon as connections end (idle ones are ended by the limits of
// server/connection_limits.h).
//
// Thread-safe. Process-wide: descriptors are the process's.
#pragma once

#include <cstdint>

namespace orbit::server {

// Starts admitting connections for this process with `reserve` descriptors kept free (>= 8), and
// raises the soft descriptor limit (RLIMIT_NOFILE) to the hard one so that the operator's limit,
// not a login shell's default, bounds the connections. Until called, accept4 is the C library's
// alone. Calling again changes the reserve.
void AdmitConnectionsKeepingFree(int reserve);

// Connections accepted and closed at once since the process started, because the descriptor
// table was full or the reserve would have been used.
std::int64_t RefusedConnections();

}  // namespace orbit::server
