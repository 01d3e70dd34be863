// The gRPC status of a refusal or a failure, the one mapping of the server's errors to the
// codes docs/design.md#service-behaviour names. Thread-safe.
#pragma once

#include <exception>
#include <string>

#include <grpcpp/grpcpp.h>

#include "server/refusal_reason.h"

namespace orbit::server {

// INVALID_ARGUMENT with `message`, which names the field and what is wrong with it.
grpc::Status InvalidArgument(std::string message);

// UNAVAILABLE: the server is shutting down (clients retry, on another replica).
grpc::Status ShuttingDown();

// CANCELLED: the caller cancelled the call or its deadline passed before its work was done; the
// work was dropped (the caller no longer waits for an answer).
grpc::Status CallerGone();

// RESOURCE_EXHAUSTED: `max_queued_calls` calls already wait for a worker (--max-queued-calls).
grpc::Status QueueFull(int max_queued_calls);

// The status for an exception thrown by core/, api/ or storage/: std::invalid_argument ->
// INVALID_ARGUMENT with its message; StoreError kNotFound -> NOT_FOUND and kAlreadyExists ->
// ALREADY_EXISTS with theirs. Any other StoreError is written to stderr whole (it names files,
// tables, statements) and the client gets a message of ours by code: kConstraint (a value the
// database refused) -> INVALID_ARGUMENT, kFull -> RESOURCE_EXHAUSTED, kBusy and kIo ->
// UNAVAILABLE (worth retrying, later or on another replica), else INTERNAL. Anything else:
// INTERNAL with the exception's message.
grpc::Status StatusFromException(const std::exception& error);

// The reason a refusal for `error` is counted under (server/refusal_reason.h), beside
// StatusFromException's code: std::invalid_argument and StoreError kConstraint -> invalid_field;
// StoreError kNotFound -> unknown_object, kAlreadyExists -> duplicate_name, any other code ->
// store; anything else -> internal.
RefusalReason RefusalReasonOf(const std::exception& error);

}  // namespace orbit::server
