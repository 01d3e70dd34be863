// LatencyHistogram: counts of durations in whole microseconds (round trips, the server's
// processing times, enrollments), from which `orbit loadtest` reports percentiles.
//
// Buckets in the manner of HdrHistogram: a value below 128 us has a bucket of its own; above,
// each power of two [2^k, 2^(k+1)) is split into 64 equal buckets, so a bucket is at most 1/64 of
// its lower edge wide. A percentile is reported as the middle of its bucket, within 0.8% of the
// true value (1/128). min(), max(), mean() and count() are exact. Memory grows with the largest
// value only (at most 3712 counters, 30 KB); Record is O(1) and never allocates once a value of
// that size was seen.
//
// Not thread-safe: one histogram per recording thread (or a lock around it), merged with Merge.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace orbit {

class LatencyHistogram {
 public:
  // Counts one duration; a negative one is counted as 0.
  void Record(std::int64_t microseconds);

  // Adds every value `other` counted.
  void Merge(const LatencyHistogram& other);

  std::uint64_t count() const { return count_; }
  // The smallest and largest values counted, exactly; 0 when empty.
  std::int64_t min() const { return count_ ? min_ : 0; }
  std::int64_t max() const { return max_; }
  // The exact mean; 0 when empty.
  double mean() const { return count_ ? static_cast<double>(sum_) / count_ : 0; }

  // The nearest-rank percentile: the value v for which ceil(percent / 100 x count()) of the
  // counted values are <= v, to within the bucket's 0.8%. Never below min() nor above max();
  // the last rank (Percentile(100)) is max() exactly. 0 when empty.
  // REQUIRES: 0 < percent <= 100.
  double Percentile(double percent) const;

 private:
  static std::size_t BucketOf(std::int64_t value);
  // The smallest and largest values bucket `index` holds.
  static std::int64_t LowestIn(std::size_t index);
  static std::int64_t HighestIn(std::size_t index);

  std::vector<std::uint64_t> counts_;  // by BucketOf
  std::uint64_t count_ = 0;
  std::int64_t min_ = 0;
  std::int64_t max_ = 0;
  // Sum of the values; an int64 of microseconds overflows after 292 000 years of latency.
  std::int64_t sum_ = 0;
};

}  // namespace orbit
