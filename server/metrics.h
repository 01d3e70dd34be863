// Metrics in Prometheus' data model (counters, gauges, histograms with fixed buckets, labels) and
// their text exposition, format 0.0.4
// (https://prometheus.io/docs/instrumenting/exposition_formats/#text-based-format).
//
// Made for per-frame updates. A metric's child for some label values is resolved once, when the
// server starts or a session opens (Family::WithLabels, which locks and allocates), and kept as
// a pointer; updating it is then a few relaxed atomic operations: no lock, no allocation, no
// string, no label lookup. Exposition (a scrape) locks each family only to walk its children,
// so it never waits for an update and an update never waits for it.
//
//   MetricsRegistry registry;
//   Counter& frames = registry.AddCounter("app_frames_total", "Frames.", {"engine"})
//                         .WithLabels({"hmm"});             // once
//   frames.Increment();                                     // per frame
//   std::string text = registry.Expose();                   // per scrape
//
// Thread-safe: every method may be called from any thread.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <deque>
#include <functional>
#include <initializer_list>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace orbit::server {

// A count that only goes up, e.g. frames processed.
class Counter {
 public:
  void Increment(std::uint64_t amount = 1) noexcept {
    value_.fetch_add(amount, std::memory_order_relaxed);
  }
  std::uint64_t value() const noexcept { return value_.load(std::memory_order_relaxed); }

 private:
  std::atomic<std::uint64_t> value_{0};
};

// Counts of observations in fixed buckets, with their sum: Prometheus' histogram. Bucket i
// counts the observations v with bounds[i-1] < v <= bounds[i] (the last, +Inf, the ones above
// every bound); the exposition adds them up into the cumulative `le` buckets Prometheus expects.
class Histogram {
 public:
  static constexpr std::size_t kMaxBounds = 30;

  // Throws std::invalid_argument unless `bounds` holds 1..kMaxBounds finite values in strictly
  // increasing order.
  explicit Histogram(std::span<const double> bounds);

  // One observation: a scan of the bounds from the smallest (observations are mostly small
  // here, so this beats a binary search), one relaxed add to the bucket, one relaxed
  // compare-and-swap loop for the sum. REQUIRES: `value` is not NaN.
  void Observe(double value) noexcept {
    std::size_t i = 0;
    while (i < bound_count_ && value > bounds_[i]) ++i;
    counts_[i].fetch_add(1, std::memory_order_relaxed);
    sum_.fetch_add(value, std::memory_order_relaxed);
  }

  // The observations so far. Read while observations go on, the buckets and the sum are each
  // exact but may be a few observations apart from one another; `count` is always the sum of
  // the buckets (so the +Inf bucket and _count agree, as Prometheus requires).
  struct Totals {
    std::vector<std::uint64_t> cumulative;  // per bound, then +Inf: observations <= the bound
    std::uint64_t count = 0;
    double sum = 0;
  };
  Totals Read() const;

  std::span<const double> bounds() const { return {bounds_.data(), bound_count_}; }

 private:
  std::size_t bound_count_;
  std::array<double, kMaxBounds> bounds_{};
  std::array<std::atomic<std::uint64_t>, kMaxBounds + 1> counts_{};
  std::atomic<double> sum_{0};
};

// A value read when the metrics are exposed, e.g. the sessions open or a queue's length.
// `read` is called on the scraping thread with the family's lock held: it must be thread-safe
// and cheap (a scrape waits for it), must not add to or expose the registry, and whatever it
// reads must outlive every later exposition.
class Gauge {
 public:
  explicit Gauge(std::function<double()> read) : read_(std::move(read)) {}
  double value() const { return read_(); }

 private:
  std::function<double()> read_;
};

// What every family has: its name, help text, label names and how it writes itself out.
class MetricFamily {
 public:
  virtual ~MetricFamily() = default;
  const std::string& name() const { return name_; }

  // Appends this family in the text format: `# HELP` and `# TYPE` lines, then one line per
  // child (histograms: their _bucket lines, _sum and _count) in the order the children were
  // created. A family without children appends nothing.
  virtual void Expose(std::string& out) const = 0;

 protected:
  MetricFamily(std::string name, std::string help, std::vector<std::string> label_names);

  // "# HELP ...\n# TYPE name `type`\n".
  void AppendHeader(std::string& out, std::string_view type) const;
  // `a="x",b="y"` for the label values `values` (escaped); "" for a family without labels.
  std::string LabelPairs(const std::vector<std::string>& values) const;
  // REQUIRES: values.size() == label_names().size(). Throws std::invalid_argument otherwise.
  std::vector<std::string> CheckedValues(std::initializer_list<std::string_view> values) const;

  const std::vector<std::string>& label_names() const { return label_names_; }

 private:
  std::string name_;
  std::string help_;
  std::vector<std::string> label_names_;
};

// The children of one metric, one per distinct list of label values.
template <typename Metric>
class Family final : public MetricFamily {
 public:
  // Counter and Histogram families: the child for `label_values` (one per label name, in
  // order), created at zero the first time. Locks and allocates: call it once and keep the
  // reference, which stays valid as long as the registry. Throws std::invalid_argument for the
  // wrong number of values.
  Metric& WithLabels(std::initializer_list<std::string_view> label_values)
    requires(!std::is_same_v<Metric, Gauge>);

  // Gauge families: adds the child for `label_values`, read by `read` at each exposition.
  // Throws std::invalid_argument for the wrong number of values or values already added.
  void Add(std::initializer_list<std::string_view> label_values, std::function<double()> read)
    requires std::is_same_v<Metric, Gauge>;

  void Expose(std::string& out) const override;

 private:
  friend class MetricsRegistry;
  Family(std::string name, std::string help, std::vector<std::string> label_names,
         std::vector<double> bounds = {})
      : MetricFamily(std::move(name), std::move(help), std::move(label_names)),
        bounds_(std::move(bounds)) {}

  struct Child {
    std::vector<std::string> label_values;
    std::unique_ptr<Metric> metric;
  };
  // REQUIRES: mutex_ held.
  Child* Find(const std::vector<std::string>& label_values);

  const std::vector<double> bounds_;  // histograms: the bucket bounds of every child
  mutable std::mutex mutex_;
  std::deque<Child> children_;  // guarded by mutex_; never shrinks
};

// The families a server exposes, in the order they were added.
class MetricsRegistry {
 public:
  MetricsRegistry() = default;
  MetricsRegistry(const MetricsRegistry&) = delete;
  MetricsRegistry& operator=(const MetricsRegistry&) = delete;

  // Each adds a family and returns it (valid as long as the registry). `name` must be a valid
  // metric name ([a-zA-Z_:][a-zA-Z0-9_:]*) not used before, each label name a valid label name
  // ([a-zA-Z_][a-zA-Z0-9_]*, not starting with "__"), histograms' not "le", and `bounds` as
  // Histogram requires; else std::invalid_argument. By Prometheus' conventions a counter's name
  // ends in _total and a metric's unit (seconds, bytes) is in its name.
  Family<Counter>& AddCounter(std::string name, std::string help,
                              std::vector<std::string> label_names = {});
  Family<Gauge>& AddGauge(std::string name, std::string help,
                          std::vector<std::string> label_names = {});
  Family<Histogram>& AddHistogram(std::string name, std::string help,
                                  std::vector<std::string> label_names, std::vector<double> bounds);

  // Every family in the text exposition format 0.0.4, served as
  // `text/plain; version=0.0.4; charset=utf-8`.
  std::string Expose() const;

 private:
  void CheckNewName(const std::string& name, const std::vector<std::string>& label_names,
                    bool histogram) const;  // REQUIRES: mutex_ held

  mutable std::mutex mutex_;
  std::vector<std::unique_ptr<MetricFamily>> families_;  // guarded by mutex_
};

// The exposition's spelling of a value: shortest round-trip digits, as Prometheus' own Go client
// writes them (strconv 'g' format: "0.005", "10", "1e-05", "1e+06"), and "+Inf", "-Inf", "NaN".
std::string FormatMetricValue(double value);

// A label value as the text format quotes it: backslash, double quote and line feed escaped as
// \\, \" and \n.
std::string EscapeLabelValue(std::string_view value);

}  // namespace orbit::server
