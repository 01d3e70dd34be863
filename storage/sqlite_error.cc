#include "storage/sqlite_error.h"

#include <string>

namespace orbit {

StoreError SqliteError(int rc, sqlite3* db, std::string_view context) {
  StoreError::Code code = StoreError::Code::kInternal;
  switch (rc & 0xff) {  // the primary code; extended codes refine it
    case SQLITE_BUSY:
    case SQLITE_LOCKED: code = StoreError::Code::kBusy; break;
    case SQLITE_FULL: code = StoreError::Code::kFull; break;
    case SQLITE_CORRUPT:
    case SQLITE_NOTADB: code = StoreError::Code::kCorrupt; break;
    case SQLITE_CONSTRAINT: code = StoreError::Code::kConstraint; break;
    case SQLITE_IOERR:
    case SQLITE_CANTOPEN:
    case SQLITE_READONLY:
    case SQLITE_PERM:
    case SQLITE_NOLFS: code = StoreError::Code::kIo; break;
    default: break;
  }
  // sqlite3_errmsg describes the last failure on `db`, which is `rc`'s when called right after it.
  const char* detail = db != nullptr ? sqlite3_errmsg(db) : sqlite3_errstr(rc);
  return StoreError(code, std::string(context) + ": " + detail);
}

}  // namespace orbit
