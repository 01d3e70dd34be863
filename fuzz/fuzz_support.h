// What the fuzz targets of the server's code share: the limits they run it with, and the reading
// of a stream of protobuf messages. Header-only.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <google/protobuf/io/coded_stream.h>
#include <google/protobuf/io/zero_copy_stream_impl_lite.h>
#include <google/protobuf/stubs/logging.h>
#include <google/protobuf/util/delimited_message_util.h>

#include "fuzz/fuzz_check.h"
#include "server/session_settings.h"

namespace orbit::fuzz {

// The server's limits (server/session_settings.h, the defaults of `orbit serve`) but for the
// pixels an uploaded image may have: 512 x 512 instead of 4096 x 4096. The budget's logic is the
// same at any limit; at the default, an input of a few hundred bytes may legitimately decode to
// 128 MiB, which under the sanitizers would only slow the search down.
inline server::ServerLimits FuzzLimits() {
  server::ServerLimits limits;
  limits.max_image_pixels = 512 * 512;
  return limits;
}

// Protobuf logs each string field that is not UTF-8 as it refuses the message: on fuzzed
// input, only noise in the log. Idempotent; call before parsing.
inline void SilenceProtobufLogs() {
  static const bool silenced = (google::protobuf::SetLogHandler(nullptr), true);
  (void)silenced;
}

// Reads `data` as a stream of length-delimited messages (each one a varint length, then that
// many bytes of the message: protobuf's writeDelimitedTo / SerializeDelimitedToOstream), as a
// gRPC stream delivers them one by one. Stops at the end of the bytes or at the first message
// that does not parse (gRPC would have refused that message and ended the stream).
template <typename Message>
std::vector<Message> ReadDelimitedMessages(const std::uint8_t* data, std::size_t size) {
  google::protobuf::io::ArrayInputStream input(data, static_cast<int>(size));
  std::vector<Message> messages;
  for (;;) {
    Message message;
    bool clean_eof = false;
    if (!google::protobuf::util::ParseDelimitedFromZeroCopyStream(&message, &input, &clean_eof)) {
      break;
    }
    messages.push_back(std::move(message));
  }
  return messages;
}

}  // namespace orbit::fuzz
