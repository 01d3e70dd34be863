// The errors of the model store other than bad arguments.
//
// Bad input (a malformed name, descriptor, azimuth, ...) is refused with std::invalid_argument,
// as everywhere in Orbit. Everything else a store can fail at is a StoreError whose code says what
// a caller can do about it; server/ maps the codes to gRPC statuses (kNotFound -> NOT_FOUND,
// kAlreadyExists -> ALREADY_EXISTS, kFull -> RESOURCE_EXHAUSTED, kBusy -> UNAVAILABLE, the rest
// -> INTERNAL / FAILED_PRECONDITION).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

#include "core/model/object_model.h"

namespace orbit {

class StoreError : public std::runtime_error {
 public:
  enum class Code {
    kNotFound,       // no object with that id or name
    kAlreadyExists,  // another object already has that name
    kBusy,           // another writer held the store for longer than the busy timeout
    kFull,           // the disk (or the database's size limit) is full
    kCorrupt,        // the file failed an integrity check or holds impossible values
    kIncompatible,   // not an Orbit model store, or written by a newer Orbit
    kConstraint,     // the database refused a write that validation let through
    kIo,             // the file cannot be opened, read, written or synced; the database
                     // server cannot be reached or the connection to it was lost
    kInternal,       // anything else SQLite reports
  };

  StoreError(Code code, const std::string& message) : std::runtime_error(message), code_(code) {}

  Code code() const { return code_; }

 private:
  Code code_;
};

// The refusals every store and its callers word alike.
// kNotFound: "no object with id ID".
inline StoreError ObjectNotFound(ObjectId id) {
  return StoreError(StoreError::Code::kNotFound, "no object with id " + std::to_string(id));
}
// kAlreadyExists: "an object named "NAME" already exists (id OWNER)".
inline StoreError NameTaken(std::string_view name, ObjectId owner) {
  return StoreError(StoreError::Code::kAlreadyExists, "an object named \"" + std::string(name) +
                                                          "\" already exists (id " +
                                                          std::to_string(owner) + ")");
}

// kAlreadyExists: "STORE holds COUNT objects: restore into an empty store".
inline StoreError StoreNotEmpty(std::string_view store, std::int64_t count) {
  return StoreError(StoreError::Code::kAlreadyExists, std::string(store) + " holds " +
                                                          std::to_string(count) +
                                                          " objects: restore into an empty store");
}

}  // namespace orbit
