#include "core/index/view_bins.h"

#include <bit>

#include "core/base/cpu_dispatch.h"

namespace orbit {

namespace {

constexpr std::size_t kLineBytes = 64;

// products[j] += q * low 4 bits of packed[j], products[half + j] += q * high 4 bits, for j <
// half: a hot loop (core/base/cpu_dispatch.h), 16 lanes of 16 bits an instruction on the AVX2
// path.
ORBIT_HOT_LOOP void AddPackedProducts(const std::uint8_t* __restrict packed, std::uint16_t q,
                                      std::uint16_t* __restrict low, std::uint16_t* __restrict high,
                                      std::size_t half) {
  for (std::size_t j = 0; j < half; ++j) {
    low[j] = static_cast<std::uint16_t>(low[j] + q * (packed[j] & 0x0F));
    high[j] = static_cast<std::uint16_t>(high[j] + q * (packed[j] >> 4));
  }
}

}  // namespace

ViewBins::ViewBins(std::span<const DescriptorValues> views)
    : views_(views.size()), half_((views.size() + 1) / 2) {
  stride_ = half_ <= kLineBytes ? std::bit_ceil(half_)
                                : (half_ + kLineBytes - 1) / kLineBytes * kLineBytes;
  lines_.resize((kDescriptorSize * stride_ + kLineBytes - 1) / kLineBytes, Line{});
  auto* bytes = reinterpret_cast<std::uint8_t*>(lines_.data());
  for (std::size_t d = 0; d < kDescriptorSize; ++d) {
    std::uint8_t* bin = bytes + d * stride_;
    for (std::size_t v = 0; v < views_; ++v) {
      const auto value = static_cast<std::uint8_t>(views[v][d] & 0x0F);
      bin[v % half_] |= static_cast<std::uint8_t>(v < half_ ? value : value << 4);
    }
  }
}

void ViewBins::AddProducts(std::size_t bin, std::uint16_t q,
                           std::span<std::uint16_t> products) const {
  RunHotLoop<AddPackedProducts>(Bin(bin), q, products.data(), products.data() + half_, half_);
}

std::uint8_t ViewBins::Value(std::size_t bin, std::size_t view) const {
  const std::uint8_t packed = Bin(bin)[view % half_];
  return view < half_ ? packed & 0x0F : packed >> 4;
}

}  // namespace orbit
