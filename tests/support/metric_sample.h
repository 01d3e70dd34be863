// One sample of a Prometheus text exposition, for the tests that scrape a server's metrics.
#pragma once

#include <gtest/gtest.h>

#include <string>

namespace orbit::testing {

// The value of the sample `series` (name and labels exactly as exposed) in `text`; -1 and a
// test failure when there is no such line.
inline double Sample(const std::string& text, const std::string& series) {
  const std::string line_start = series + " ";
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t end = text.find('\n', at);
    if (text.compare(at, line_start.size(), line_start) == 0) {
      return std::stod(text.substr(at + line_start.size(), end - at - line_start.size()));
    }
    at = end == std::string::npos ? text.size() : end + 1;
  }
  ADD_FAILURE() << "no sample " << series << " in\n" << text;
  return -1;
}

}  // namespace orbit::testing
