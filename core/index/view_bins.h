// ViewBins: an object's view descriptors bin by bin, 4 bits a value, for the similarity rows
// (core/index/similarity_rows.h): a frame's row of Tanimoto coefficients with an object's views
// reads only the frame's non-zero bins (about 21 of 144 in a COIL-100 CEDD), and each bin of up to
// 128 views is one cache line, where a byte a value took two at 72 views. Where hundreds of
// sessions look at different objects, these reads come from memory (docs/results/load.md,
// "Cold reads and the floor", measures the gain).
//
// A CEDD value is at most 7 (core/descriptor/descriptor.h), so 4 bits hold it exactly and every
// product below is the one a byte a value gives.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/descriptor/descriptor.h"

namespace orbit {

class ViewBins {
 public:
  ViewBins() = default;
  // REQUIRES: every value of every descriptor at most 7 (ValidateDescriptorValues).
  explicit ViewBins(std::span<const DescriptorValues> views);

  std::size_t view_count() const { return views_; }

  // The length `products` must have: view_count() rounded up to an even count (the products
  // past view_count() are scratch, left at whatever they become).
  std::size_t padded_count() const { return 2 * half_; }

  // products[v] += q * (view v's value in `bin`) for every view v, exactly in 16 bits when the
  // products summed over a descriptor stay below 65536 (144 x 7 x 7 = 7056 do).
  // REQUIRES: bin < kDescriptorSize, q <= 7, products.size() >= padded_count().
  void AddProducts(std::size_t bin, std::uint16_t q, std::span<std::uint16_t> products) const;

  // View v's value in `bin` (for tests and checks; the rows use AddProducts).
  std::uint8_t Value(std::size_t bin, std::size_t view) const;

 private:
  // A bin is `stride_` bytes, byte j holding view j in its low 4 bits and view j + half_ in
  // its high 4: stride_ is half_ rounded up to a power of two up to 64 bytes, or to a multiple
  // of 64, so that on 64-byte-aligned storage no bin straddles more cache lines than it must.
  struct alignas(64) Line {
    std::uint8_t bytes[64];
  };
  const std::uint8_t* Bin(std::size_t bin) const {
    return reinterpret_cast<const std::uint8_t*>(lines_.data()) + bin * stride_;
  }

  std::size_t views_ = 0;
  std::size_t half_ = 0;
  std::size_t stride_ = 0;
  std::vector<Line> lines_;
};

}  // namespace orbit
