#include "server/error_status.h"

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
    switch (store->code()) {
      case StoreError::Code::kNotFound: return {grpc::StatusCode::NOT_FOUND, error.what()};
      case StoreError::Code::kAlreadyExists:
        return {grpc::StatusCode::ALREADY_EXISTS, error.what()};
      case StoreError::Code::kFull: return {grpc::StatusCode::RESOURCE_EXHAUSTED, error.what()};
      case StoreError::Code::kBusy:
      case StoreError::Code::kIo: return {grpc::StatusCode::UNAVAILABLE, error.what()};
      default: return {grpc::StatusCode::INTERNAL, error.what()};
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
      default: return RefusalReason::kStore;
    }
  }
  return RefusalReason::kInternal;
}

}  // namespace orbit::server
