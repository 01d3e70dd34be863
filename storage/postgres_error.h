// PostgreSQL failures as StoreErrors: one place decides what a SQLSTATE means for the caller.
#pragma once

#include <string_view>

#include "storage/store_error.h"

namespace orbit {

// The StoreError for a statement the server refused with `sqlstate` (its five-character code;
// "" when there is none, as when the connection was lost), with the message
// "<context>: <message>". Unique violations are kAlreadyExists, other integrity and data errors
// kConstraint, lock and serialisation timeouts kBusy, a full disk kFull, corruption kCorrupt, a
// lost connection and the server's I/O errors kIo, the rest kInternal.
StoreError PostgresError(std::string_view sqlstate, std::string_view message,
                         std::string_view context);

}  // namespace orbit
