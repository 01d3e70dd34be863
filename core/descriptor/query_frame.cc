#include "core/descriptor/query_frame.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "core/base/angles.h"

namespace orbit {
namespace {

// "<field> must be in <range>, got <value>".
std::string OutOfRange(std::string_view field, std::string_view range, double value) {
  std::ostringstream message;
  message << field << " must be in " << range << ", got " << value;
  return message.str();
}

}  // namespace

void ValidateQueryFrame(const QueryFrame& frame, const QueryFrameFields& fields) {
  if (frame.azimuth && !std::isfinite(*frame.azimuth)) {
    throw std::invalid_argument(std::string(fields.azimuth) + " must be a finite number");
  }
  // Written so that NaN fails.
  if (frame.noise_sigma && !(*frame.noise_sigma >= 0 && *frame.noise_sigma <= kMaxNoiseSigma)) {
    throw std::invalid_argument(
        OutOfRange(fields.noise_sigma,
                   "[0, " + std::to_string(static_cast<int>(kMaxNoiseSigma)) + "] grey levels",
                   *frame.noise_sigma));
  }
  if (frame.blur && !(*frame.blur >= 0 && *frame.blur <= kMaxBlur)) {
    throw std::invalid_argument(OutOfRange(
        fields.blur, "[0, " + std::to_string(static_cast<int>(kMaxBlur)) + "]", *frame.blur));
  }
  ValidateDescriptorValues(frame.descriptor.values, fields.descriptor);
}

std::optional<double> MeasuredTurn(const QueryFrame& from, const QueryFrame& to) {
  if (!from.azimuth || !to.azimuth) return std::nullopt;
  return AzimuthChange(*from.azimuth, *to.azimuth);
}

}  // namespace orbit
