#include "cli/latency_histogram.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace orbit {
namespace {

constexpr int kExactBits = 7;                          // values below 2^7 = 128 are exact
constexpr std::int64_t kExactLimit = 1 << kExactBits;  // 128
constexpr std::int64_t kSubBuckets = kExactLimit / 2;  // 64 buckets per power of two above

}  // namespace

std::size_t LatencyHistogram::BucketOf(std::int64_t value) {
  if (value < kExactLimit) return static_cast<std::size_t>(value);
  // shift >= 1 is how far `value` must move right to land in [64, 128).
  const int shift = std::bit_width(static_cast<std::uint64_t>(value)) - kExactBits;
  return static_cast<std::size_t>(kExactLimit + (shift - 1) * kSubBuckets +
                                  ((value >> shift) - kSubBuckets));
}

std::int64_t LatencyHistogram::LowestIn(std::size_t index) {
  const auto i = static_cast<std::int64_t>(index);
  if (i < kExactLimit) return i;
  const std::int64_t shift = (i - kExactLimit) / kSubBuckets + 1;
  const std::int64_t sub = (i - kExactLimit) % kSubBuckets + kSubBuckets;
  return sub << shift;
}

std::int64_t LatencyHistogram::HighestIn(std::size_t index) {
  if (static_cast<std::int64_t>(index) < kExactLimit) return LowestIn(index);
  const std::int64_t shift = (static_cast<std::int64_t>(index) - kExactLimit) / kSubBuckets + 1;
  return LowestIn(index) + (std::int64_t{1} << shift) - 1;
}

void LatencyHistogram::Record(std::int64_t microseconds) {
  const std::int64_t value = std::max<std::int64_t>(0, microseconds);
  const std::size_t bucket = BucketOf(value);
  if (bucket >= counts_.size()) counts_.resize(bucket + 1, 0);
  ++counts_[bucket];
  min_ = count_ == 0 ? value : std::min(min_, value);
  max_ = std::max(max_, value);
  sum_ += value;
  ++count_;
}

void LatencyHistogram::Merge(const LatencyHistogram& other) {
  if (other.count_ == 0) return;
  if (other.counts_.size() > counts_.size()) counts_.resize(other.counts_.size(), 0);
  for (std::size_t i = 0; i < other.counts_.size(); ++i) counts_[i] += other.counts_[i];
  min_ = count_ == 0 ? other.min_ : std::min(min_, other.min_);
  max_ = std::max(max_, other.max_);
  sum_ += other.sum_;
  count_ += other.count_;
}

double LatencyHistogram::Percentile(double percent) const {
  if (count_ == 0) return 0;
  // percent x count first, so that whole products stay exact (99 x 100 / 100 is 99, where
  // 0.99 x 100 is not); the small margin keeps 99.9 x 1000 / 100 from rounding up to 1000.
  const double exact_rank = percent * static_cast<double>(count_) / 100.0;
  const auto rank =
      std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::ceil(exact_rank - 1e-9)));
  if (rank >= count_) return static_cast<double>(max_);  // the largest value, known exactly
  std::uint64_t seen = 0;
  for (std::size_t i = 0; i < counts_.size(); ++i) {
    seen += counts_[i];
    if (seen >= rank) {
      const double middle = (static_cast<double>(LowestIn(i)) + HighestIn(i)) / 2;
      return std::clamp(middle, static_cast<double>(min_), static_cast<double>(max_));
    }
  }
  return static_cast<double>(max_);
}

}  // namespace orbit
