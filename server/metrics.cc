#include "server/metrics.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

namespace orbit::server {
namespace {

bool IsNameStart(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
bool IsDigit(char c) { return c >= '0' && c <= '9'; }

bool IsMetricName(std::string_view name) {
  if (name.empty() || !(IsNameStart(name[0]) || name[0] == ':')) return false;
  for (char c : name) {
    if (!(IsNameStart(c) || IsDigit(c) || c == ':')) return false;
  }
  return true;
}

bool IsLabelName(std::string_view name) {
  if (name.empty() || !IsNameStart(name[0]) || name.starts_with("__")) return false;
  for (char c : name) {
    if (!(IsNameStart(c) || IsDigit(c))) return false;
  }
  return true;
}

void CheckBounds(std::span<const double> bounds) {
  if (bounds.empty() || bounds.size() > Histogram::kMaxBounds) {
    throw std::invalid_argument("a histogram needs 1 to " + std::to_string(Histogram::kMaxBounds) +
                                " bucket bounds");
  }
  for (std::size_t i = 0; i < bounds.size(); ++i) {
    if (!std::isfinite(bounds[i]) || (i > 0 && !(bounds[i] > bounds[i - 1]))) {
      throw std::invalid_argument("histogram bounds must be finite and strictly increasing");
    }
  }
}

std::string EscapeHelp(std::string_view help) {
  std::string out;
  for (char c : help) {
    switch (c) {
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      default: out += c;
    }
  }
  return out;
}

void AppendInteger(std::string& out, std::uint64_t value) {
  char digits[24];
  const auto end = std::to_chars(digits, digits + sizeof digits, value).ptr;
  out.append(digits, end);
}

// `name` + `{pairs}` (nothing when there are no pairs) + " " + value + "\n".
void AppendSample(std::string& out, std::string_view name, std::string_view suffix,
                  std::string_view pairs, std::string_view value) {
  out += name;
  out += suffix;
  if (!pairs.empty()) {
    out += '{';
    out += pairs;
    out += '}';
  }
  out += ' ';
  out += value;
  out += '\n';
}

}  // namespace

std::string FormatMetricValue(double value) {
  if (std::isnan(value)) return "NaN";
  if (std::isinf(value)) return value > 0 ? "+Inf" : "-Inf";
  if (value == 0) return "0";
  // Go's strconv.FormatFloat(value, 'g', -1, 64): the shortest digits that read back as
  // `value`, in exponent form when the decimal exponent is below -4 or at least 6.
  char text[64];
  char* end = std::to_chars(text, text + sizeof text, value, std::chars_format::scientific).ptr;
  const char* digits = std::find(text, end, 'e') + 1;  // "d.ddde-05": sign, at least 2 digits
  const bool negative = *digits == '-';
  int exponent = 0;
  std::from_chars(digits + 1, end, exponent);
  if (negative) exponent = -exponent;
  if (exponent < -4 || exponent >= 6) return std::string(text, end);
  end = std::to_chars(text, text + sizeof text, value, std::chars_format::fixed).ptr;
  return std::string(text, end);
}

std::string EscapeLabelValue(std::string_view value) {
  std::string out;
  out.reserve(value.size());
  for (char c : value) {
    switch (c) {
      case '\\': out += "\\\\"; break;
      case '"': out += "\\\""; break;
      case '\n': out += "\\n"; break;
      default: out += c;
    }
  }
  return out;
}

// ---- Histogram ----

Histogram::Histogram(std::span<const double> bounds) : bound_count_(bounds.size()) {
  CheckBounds(bounds);
  std::copy(bounds.begin(), bounds.end(), bounds_.begin());
}

Histogram::Totals Histogram::Read() const {
  Totals totals;
  totals.cumulative.reserve(bound_count_ + 1);
  for (std::size_t i = 0; i <= bound_count_; ++i) {
    totals.count += counts_[i].load(std::memory_order_relaxed);
    totals.cumulative.push_back(totals.count);
  }
  totals.sum = sum_.load(std::memory_order_relaxed);
  return totals;
}

// ---- MetricFamily ----

MetricFamily::MetricFamily(std::string name, std::string help, std::vector<std::string> label_names)
    : name_(std::move(name)), help_(std::move(help)), label_names_(std::move(label_names)) {}

void MetricFamily::AppendHeader(std::string& out, std::string_view type) const {
  out += "# HELP ";
  out += name_;
  out += ' ';
  out += EscapeHelp(help_);
  out += "\n# TYPE ";
  out += name_;
  out += ' ';
  out += type;
  out += '\n';
}

std::string MetricFamily::LabelPairs(const std::vector<std::string>& values) const {
  std::string pairs;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i > 0) pairs += ',';
    pairs += label_names_[i];
    pairs += "=\"";
    pairs += EscapeLabelValue(values[i]);
    pairs += '"';
  }
  return pairs;
}

std::vector<std::string> MetricFamily::CheckedValues(
    std::initializer_list<std::string_view> values) const {
  if (values.size() != label_names_.size()) {
    throw std::invalid_argument(name_ + " takes " + std::to_string(label_names_.size()) +
                                " label values, not " + std::to_string(values.size()));
  }
  return std::vector<std::string>(values.begin(), values.end());
}

// ---- Family ----

template <typename Metric>
typename Family<Metric>::Child* Family<Metric>::Find(const std::vector<std::string>& label_values) {
  for (Child& child : children_) {
    if (child.label_values == label_values) return &child;
  }
  return nullptr;
}

template <typename Metric>
Metric& Family<Metric>::WithLabels(std::initializer_list<std::string_view> label_values)
  requires(!std::is_same_v<Metric, Gauge>)
{
  std::vector<std::string> values = CheckedValues(label_values);
  std::lock_guard lock(mutex_);
  if (Child* found = Find(values)) return *found->metric;
  std::unique_ptr<Metric> metric;
  if constexpr (std::is_same_v<Metric, Histogram>) {
    metric = std::make_unique<Histogram>(bounds_);
  } else {
    metric = std::make_unique<Metric>();
  }
  children_.push_back({std::move(values), std::move(metric)});
  return *children_.back().metric;
}

template <typename Metric>
void Family<Metric>::Add(std::initializer_list<std::string_view> label_values,
                         std::function<double()> read)
  requires std::is_same_v<Metric, Gauge>
{
  std::vector<std::string> values = CheckedValues(label_values);
  std::lock_guard lock(mutex_);
  if (Find(values) != nullptr) {
    throw std::invalid_argument(name() + " already has a gauge for these label values");
  }
  children_.push_back({std::move(values), std::make_unique<Gauge>(std::move(read))});
}

template <>
void Family<Counter>::Expose(std::string& out) const {
  std::lock_guard lock(mutex_);
  if (children_.empty()) return;
  AppendHeader(out, "counter");
  std::string value;
  for (const Child& child : children_) {
    value.clear();
    AppendInteger(value, child.metric->value());
    AppendSample(out, name(), "", LabelPairs(child.label_values), value);
  }
}

template <>
void Family<Gauge>::Expose(std::string& out) const {
  std::lock_guard lock(mutex_);
  if (children_.empty()) return;
  AppendHeader(out, "gauge");
  for (const Child& child : children_) {
    AppendSample(out, name(), "", LabelPairs(child.label_values),
                 FormatMetricValue(child.metric->value()));
  }
}

template <>
void Family<Histogram>::Expose(std::string& out) const {
  std::lock_guard lock(mutex_);
  if (children_.empty()) return;
  AppendHeader(out, "histogram");
  std::string value;
  for (const Child& child : children_) {
    const std::string pairs = LabelPairs(child.label_values);
    const std::string prefix = pairs.empty() ? "le=\"" : pairs + ",le=\"";
    const Histogram::Totals totals = child.metric->Read();
    for (std::size_t i = 0; i < totals.cumulative.size(); ++i) {
      value.clear();
      AppendInteger(value, totals.cumulative[i]);
      const std::string bound =
          i < bounds_.size() ? FormatMetricValue(bounds_[i]) : std::string("+Inf");
      AppendSample(out, name(), "_bucket", prefix + bound + "\"", value);
    }
    AppendSample(out, name(), "_sum", pairs, FormatMetricValue(totals.sum));
    value.clear();
    AppendInteger(value, totals.count);
    AppendSample(out, name(), "_count", pairs, value);
  }
}

template class Family<Counter>;
template class Family<Gauge>;
template class Family<Histogram>;

// ---- MetricsRegistry ----

void MetricsRegistry::CheckNewName(const std::string& name,
                                   const std::vector<std::string>& label_names,
                                   bool histogram) const {
  if (!IsMetricName(name)) throw std::invalid_argument("'" + name + "' is not a metric name");
  for (const auto& family : families_) {
    if (family->name() == name) throw std::invalid_argument(name + " is already registered");
  }
  for (std::size_t i = 0; i < label_names.size(); ++i) {
    const std::string& label = label_names[i];
    if (!IsLabelName(label) || (histogram && label == "le")) {
      throw std::invalid_argument(name + ": '" + label + "' cannot be a label name");
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (label_names[j] == label)
        throw std::invalid_argument(name + ": label " + label + " twice");
    }
  }
}

Family<Counter>& MetricsRegistry::AddCounter(std::string name, std::string help,
                                             std::vector<std::string> label_names) {
  std::lock_guard lock(mutex_);
  CheckNewName(name, label_names, false);
  std::unique_ptr<Family<Counter>> family(
      new Family<Counter>(std::move(name), std::move(help), std::move(label_names)));
  Family<Counter>& added = *family;
  families_.push_back(std::move(family));
  return added;
}

Family<Gauge>& MetricsRegistry::AddGauge(std::string name, std::string help,
                                         std::vector<std::string> label_names) {
  std::lock_guard lock(mutex_);
  CheckNewName(name, label_names, false);
  std::unique_ptr<Family<Gauge>> family(
      new Family<Gauge>(std::move(name), std::move(help), std::move(label_names)));
  Family<Gauge>& added = *family;
  families_.push_back(std::move(family));
  return added;
}

Family<Histogram>& MetricsRegistry::AddHistogram(std::string name, std::string help,
                                                 std::vector<std::string> label_names,
                                                 std::vector<double> bounds) {
  std::lock_guard lock(mutex_);
  CheckNewName(name, label_names, true);
  CheckBounds(bounds);
  std::unique_ptr<Family<Histogram>> family(new Family<Histogram>(
      std::move(name), std::move(help), std::move(label_names), std::move(bounds)));
  Family<Histogram>& added = *family;
  families_.push_back(std::move(family));
  return added;
}

std::string MetricsRegistry::Expose() const {
  std::lock_guard lock(mutex_);
  std::string out;
  for (const auto& family : families_) family->Expose(out);
  return out;
}

}  // namespace orbit::server
