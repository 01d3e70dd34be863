#include "server/error_status.h"

#include <iostream>

#include <stdexcept>

#include "storage/store_error.h"

namespace orbit::server {

grpc::Status InvalidArgument(std::string message) {
  return {grpc::StatusCode::INVALID_ARGUMENT, std::move(message)};
}

grpc::Status ShuttingDown() {
  return {grpc::StatusCode::UNAVAILABLE, "the server is shutting down"};
}

grpc::Status CallerGone() {
  return {grpc::StatusCode::CANCELLED,
          "the call was cancelled or its deadline passed before its work was done; dropped"};
}

grpc::Status QueueFull(int max_queued_calls) {
  return {grpc::StatusCode::RESOURCE_EXHAUSTED,
          "the server is busy: " + std::to_string(max_queued_calls) +
              " calls already wait for a worker (--max-queued-calls " +
              std::to_string(max_queued_calls) + "); retry later"};
}

grpc::Status StatusFromException(const std::exception& error) {
  if (dynamic_cast<const std::invalid_argument*>(&error) != nullptr) {
    return InvalidArgument(error.what());
  }
  if (const auto* store = dynamic_cast<const StoreError*>(&error)) {
    using Code = StoreError::Code;
    switch (store->code()) {
      case Code::kNotFound: return {grpc::StatusCode::NOT_FOUND, error.what()};
      case Code::kAlreadyExists: return {grpc::StatusCode::ALREADY_EXISTS, error.what()};
      default: break;
    }
    // The store's own words name its files, tables and statements: they go to the operator's
    // log, and the client gets what it can act on.
    std::cerr << "orbit serve: model store: " << error.what() << std::endl;
    switch (store->code()) {
      case Code::kConstraint:
        return InvalidArgument(
            "the model store refused the values of this request; nothing "
            "was stored");
      case Code::kFull:
        return {grpc::StatusCode::RESOURCE_EXHAUSTED,
                "the model store is full; nothing was stored"};
      case Code::kBusy:
        return {grpc::StatusCode::UNAVAILABLE,
                "the model store is busy; retry later or on another replica"};
      case Code::kIo:
        return {grpc::StatusCode::UNAVAILABLE,
                "the model store cannot be reached or written; retry later or on another "
                "replica"};
      default:
        return {grpc::StatusCode::INTERNAL, "the model store failed; the server's log says why"};
    }
  }
  return {grpc::StatusCode::INTERNAL, error.what()};
}

RefusalReason RefusalReasonOf(const std::exception& error) {
  if (dynamic_cast<const std::invalid_argument*>(&error) != nullptr) {
    return RefusalReason::kInvalidField;
  }
  if (const auto* store = dynamic_cast<const StoreError*>(&error)) {
    switch (store->code()) {
      case StoreError::Code::kNotFound: return RefusalReason::kUnknownObject;
      case StoreError::Code::kAlreadyExists: return RefusalReason::kDuplicateName;
      case StoreError::Code::kConstraint: return RefusalReason::kInvalidField;
      default: return RefusalReason::kStore;
    }
  }
  return RefusalReason::kInternal;
}

}  // namespace orbit::server
