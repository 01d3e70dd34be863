// SQLite result codes as StoreErrors: one place decides what a failure means for the caller.
#pragma once

#include <string_view>

#include <sqlite3.h>

#include "storage/store_error.h"

namespace orbit {

// The StoreError for result code `rc` (not SQLITE_OK), with the message
// "<context>: <SQLite's message>". `db` may be null (then SQLite's generic text for rc is used).
StoreError SqliteError(int rc, sqlite3* db, std::string_view context);

}  // namespace orbit
