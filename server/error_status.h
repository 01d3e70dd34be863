// The gRPC status of a refusal or a failure, the one mapping of the server's errors to the
// codes SPEC.md's "Service behaviour" names. Pure functions, thread-safe.
#pragma once

#include <exception>
#include <string>

#include <grpcpp/grpcpp.h>

namespace orbit::server {

// INVALID_ARGUMENT with `message`, which names the field and what is wrong with it.
grpc::Status InvalidArgument(std::string message);

// The status for an exception thrown by core/, api/ or storage/: std::invalid_argument ->
// INVALID_ARGUMENT; StoreError by code (not found -> NOT_FOUND, already exists ->
// ALREADY_EXISTS, full -> RESOURCE_EXHAUSTED, busy -> UNAVAILABLE, else INTERNAL); anything else
// INTERNAL. The message is the exception's.
grpc::Status StatusFromException(const std::exception& error);

}  // namespace orbit::server
