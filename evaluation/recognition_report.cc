#include "evaluation/recognition_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <map>
#include <sstream>
#include <stdexcept>

#include "evaluation/evaluation_report.h"

namespace orbit {
namespace {

// `text` as one CSV field, quoted (RFC 4180) when it holds a comma, a quote or a line break, or
// starts or ends with a blank, which a reader would trim.
std::string CsvField(const std::string& text) {
  const bool plain = text.find_first_of(",\"\r\n") == std::string::npos &&
                     (text.empty() || (text.front() != ' ' && text.back() != ' '));
  if (plain) return text;
  std::string quoted = "\"";
  for (const char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + '"';
}

std::string Percent(int count, int total) {
  if (total == 0) return "-";
  char text[16];
  std::snprintf(text, sizeof text, "%.1f", 100.0 * count / total);
  return text;
}

std::string Degrees(double value) {
  if (std::isnan(value)) return "-";
  char text[16];
  std::snprintf(text, sizeof text, "%.1f", value);
  return text;
}

// The q-quantile of `values` (nearest rank), NaN when empty.
double Quantile(std::vector<double> values, double q) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(values.size())));
  return values[std::clamp<std::size_t>(rank, 1, values.size()) - 1];
}

}  // namespace

std::string RecognitionMarkdown(const EvaluationReport& report) {
  std::ostringstream out;
  out << "\n### Recognition (%): known queries right and accepted / rejected / accepted but "
         "wrong; unknown queries rejected / accepted; pose error of known hits (degrees)\n\n"
      << "| method | variant | distortion | n | known right+accepted | known rejected | "
         "known accepted wrong | unknown rejected | unknown accepted | pose median | pose p90 |\n"
      << "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const EvaluationCell& cell : report.cells) {
    int rejected_known = 0;
    std::vector<double> pose_errors;
    for (const QueryVerdict& verdict : cell.verdicts) {
      if (verdict.known && verdict.decision == Decision::kUnknown) ++rejected_known;
      if (!std::isnan(verdict.pose_error)) pose_errors.push_back(verdict.pose_error);
    }
    const int accepted_unknown = cell.unknown_trials - cell.rejected;
    out << "| " << cell.method << " | " << VariantName(cell.variant) << " | "
        << DistortionLabel(cell.distortion) << " | " << cell.n << " | "
        << Percent(cell.accepted, cell.trials) << " | " << Percent(rejected_known, cell.trials)
        << " | " << Percent(cell.accepted_wrong, cell.trials) << " | "
        << Percent(cell.rejected, cell.unknown_trials) << " | "
        << Percent(accepted_unknown, cell.unknown_trials) << " | "
        << Degrees(Quantile(pose_errors, 0.5)) << " | " << Degrees(Quantile(pose_errors, 0.9))
        << " |\n";
  }
  if (report.query_sequences > 0) {
    // A captured frame's azimuth is its device's reading: only differences between frames
    // matter (docs/capture.md), so it does not say from which side of the model the camera saw
    // the object, and there is no truth to measure the pose against.
    out << "\nPose error: not measured for captured queries (`--queries`): their azimuths are the "
           "device's readings, which give the turns between frames, not the side of the model "
           "each frame shows.\n";
  }
  return out.str();
}

std::vector<ReliabilityBin> Reliability(const std::vector<const EvaluationCell*>& cells) {
  std::vector<ReliabilityBin> bins(10);
  std::vector<double> confidence_sum(10, 0);
  for (int b = 0; b < 10; ++b) bins[b] = {b / 10.0, (b + 1) / 10.0, 0, 0, 0};
  for (const EvaluationCell* cell : cells) {
    for (const QueryVerdict& verdict : cell->verdicts) {
      const int b = std::clamp(static_cast<int>(verdict.confidence * 10), 0, 9);
      ++bins[b].updates;
      bins[b].right += verdict.hit;
      confidence_sum[b] += verdict.confidence;
    }
  }
  for (int b = 0; b < 10; ++b) {
    if (bins[b].updates > 0) bins[b].mean_confidence = confidence_sum[b] / bins[b].updates;
  }
  return bins;
}

std::optional<ReliabilityGap> LargestReliabilityGap(const std::vector<ReliabilityBin>& bins,
                                                    int least) {
  std::optional<ReliabilityGap> largest;
  for (const ReliabilityBin& bin : bins) {
    if (bin.updates < least || bin.updates == 0) continue;
    const double points =
        100 * (static_cast<double>(bin.right) / bin.updates - bin.mean_confidence);
    if (!largest || std::abs(points) > std::abs(largest->points)) largest = {bin, points};
  }
  return largest;
}

std::string ReliabilityMarkdown(const EvaluationReport& report) {
  std::map<std::string, std::vector<const EvaluationCell*>> by_method;
  std::vector<std::string> order;
  for (const EvaluationCell& cell : report.cells) {
    const std::string key = cell.method + " on " + std::string(VariantName(cell.variant));
    if (by_method.find(key) == by_method.end()) order.push_back(key);
    by_method[key].push_back(&cell);
  }
  std::ostringstream out;
  out << "\n### Reliability of the confidence: every update of known and unknown queries, all "
         "distortions and n (right = a known query whose top-1 object is right)\n";
  for (const std::string& key : order) {
    out << "\n"
        << key << "\n\n| confidence | updates | mean confidence | right (%) |\n"
        << "|---|---|---|---|\n";
    const std::vector<ReliabilityBin> bins = Reliability(by_method[key]);
    for (const ReliabilityBin& bin : bins) {
      if (bin.updates == 0) continue;
      char row[128];
      std::snprintf(row, sizeof row, "| %.1f-%.1f | %d | %.3f | %s |\n", bin.low, bin.high,
                    bin.updates, bin.mean_confidence, Percent(bin.right, bin.updates).c_str());
      out << row;
    }
    const std::optional<ReliabilityGap> gap = LargestReliabilityGap(bins, kReliabilityGapLeast);
    char line[192];
    if (gap) {
      std::snprintf(line, sizeof line,
                    "\nFarthest from the share right, of the bins of at least %d updates: "
                    "%.1f-%.1f, %+.1f points (share right less mean confidence).\n",
                    kReliabilityGapLeast, gap->bin.low, gap->bin.high, gap->points);
    } else {
      std::snprintf(line, sizeof line,
                    "\nNo bin holds %d updates: too few to judge the "
                    "confidence by.\n",
                    kReliabilityGapLeast);
    }
    out << line;
  }
  return out.str();
}

LineFigure RecognitionCurves(const EvaluationReport& report) {
  static constexpr double kTargets[] = {0.001, 0.01, 0.02, 0.05, 0.1,  0.15, 0.2,
                                        0.3,   0.4,  0.5,  0.7,  0.85, 1.0};
  LineFigure figure;
  figure.title =
      "Known queries right and accepted against unknown queries accepted, as the "
      "target false-accept rate goes from 0.001 to 1";
  std::map<std::string, std::size_t> panel_of;
  for (const EvaluationCell& cell : report.cells) {
    if (cell.trials == 0 || cell.unknown_trials == 0) continue;
    const std::string title =
        std::string(VariantName(cell.variant)) + ", " + DistortionLabel(cell.distortion);
    auto [at, added] = panel_of.emplace(title, figure.panels.size());
    if (added) {
      LinePanel& panel = figure.panels.emplace_back();
      panel.title = title;
      panel.x_label = "unknown queries accepted (%)";
      panel.y_label = "known right and accepted (%)";
      for (int x = 0; x <= 100; x += 25) panel.ticks.push_back({x / 100.0, std::to_string(x)});
    }
    LineSeries series{cell.method + " n=" + std::to_string(cell.n), {}};
    for (const double target : kTargets) {
      int right = 0, accepted_unknown = 0;
      for (const QueryVerdict& v : cell.verdicts) {
        const bool accepted = v.unknown_p_value <= target;
        if (v.known) right += v.hit && accepted;
        if (!v.known) accepted_unknown += accepted;
      }
      series.points.push_back({static_cast<double>(accepted_unknown) / cell.unknown_trials,
                               static_cast<double>(right) / cell.trials});
    }
    figure.panels[at->second].series.push_back(std::move(series));
  }
  if (figure.panels.empty()) {
    throw std::invalid_argument(
        "the recognition curves need known and unknown queries "
        "(orbit eval --unknown-objects)");
  }
  figure.columns = static_cast<int>(std::min<std::size_t>(figure.panels.size(), 3));
  return figure;
}

std::optional<UnknownSeparation> SeparationOf(const EvaluationCell& cell) {
  std::vector<double> known_right, unknown;
  int known = 0;
  for (const QueryVerdict& verdict : cell.verdicts) {
    if (std::isnan(verdict.unknown_statistic)) return std::nullopt;
    if (!verdict.known) {
      unknown.push_back(verdict.unknown_statistic);
    } else {
      ++known;
      if (verdict.hit) known_right.push_back(verdict.unknown_statistic);
    }
  }
  if (known == 0 || unknown.empty()) return std::nullopt;
  std::sort(unknown.begin(), unknown.end());
  UnknownSeparation separation;
  double pairs = 0;  // pairs (known right, unknown) in which the known one is lower, ties half
  for (const double u : known_right) {
    const auto [low, high] = std::equal_range(unknown.begin(), unknown.end(), u);
    pairs += static_cast<double>(unknown.end() - high) + 0.5 * static_cast<double>(high - low);
  }
  separation.area =
      known_right.empty()
          ? 0
          : pairs / (static_cast<double>(known_right.size()) * static_cast<double>(unknown.size()));
  const double unknowns = static_cast<double>(unknown.size());
  for (const double rejected : kSeparationRejected) {
    // The threshold may accept the `accepted` lowest unknown U values, so it lies just below
    // the next one; a margin of 1e-9 keeps (1 - 0.8) x 10, 1.9999999999999996 in doubles,
    // from rounding down to 1.
    const auto accepted = static_cast<std::size_t>(std::floor((1 - rejected) * unknowns + 1e-9));
    const auto below = [&](double u) {
      return accepted >= unknown.size() || u < unknown[accepted];
    };
    separation.known_right.push_back(
        static_cast<double>(std::count_if(known_right.begin(), known_right.end(), below)) /
        static_cast<double>(known));
  }
  return separation;
}

std::string SeparationMarkdown(const EvaluationReport& report) {
  std::ostringstream rows;
  for (const EvaluationCell& cell : report.cells) {
    const std::optional<UnknownSeparation> separation = SeparationOf(cell);
    if (!separation) continue;
    char area[16];
    std::snprintf(area, sizeof area, "%.3f", separation->area);
    rows << "| " << cell.method << " | " << VariantName(cell.variant) << " | "
         << DistortionLabel(cell.distortion) << " | " << cell.n << " | " << area;
    for (const double share : separation->known_right) {
      char text[16];
      std::snprintf(text, sizeof text, "%.1f", 100 * share);
      rows << " | " << text;
    }
    rows << " |\n";
  }
  if (rows.str().empty()) return "";
  std::ostringstream out;
  out << "\n### What a threshold on the unknown statistic could do, in hindsight: each cell's own "
         "queries choose it; known queries right (%) below the threshold that rejects that share "
         "of its unknown queries\n\n"
      << "| method | variant | distortion | n | area under the curve |";
  for (const double rejected : kSeparationRejected) out << " " << 100 * rejected << "% rejected |";
  out << "\n|---|---|---|---|---";
  for (std::size_t i = 0; i < std::size(kSeparationRejected); ++i) out << "|---";
  out << "|\n" << rows.str();
  return out.str();
}

void WriteVerdictsCsv(const EvaluationReport& report, std::ostream& out) {
  out << "method,variant,distortion,n,object,answer,known,hit,decision,unknown_statistic,"
         "unknown_p_value,confidence,pose_error,pose_spread,noise_sigma,blur\n";
  char numbers[160];
  for (const EvaluationCell& cell : report.cells) {
    for (const QueryVerdict& v : cell.verdicts) {
      out << cell.method << ',' << VariantName(cell.variant) << ',' << cell.distortion << ','
          << cell.n << ',' << CsvField(v.object) << ',' << CsvField(v.answer) << ',' << v.known
          << ',' << v.hit << ',' << DecisionName(v.decision) << ',';
      for (const double value : {v.unknown_statistic, v.unknown_p_value}) {
        if (!std::isnan(value)) {
          std::snprintf(numbers, sizeof numbers, "%.6g", value);
          out << numbers;
        }
        out << ',';
      }
      std::snprintf(numbers, sizeof numbers, "%.6g", v.confidence);
      out << numbers << ',' << (std::isnan(v.pose_error) ? "" : Degrees(v.pose_error)) << ','
          << (std::isnan(v.pose_spread) ? "" : Degrees(v.pose_spread)) << ',';
      if (!std::isnan(v.noise_sigma)) {
        std::snprintf(numbers, sizeof numbers, "%.3f", v.noise_sigma);
        out << numbers;
      }
      out << ',';
      if (!std::isnan(v.blur)) {
        std::snprintf(numbers, sizeof numbers, "%.3f", v.blur);
        out << numbers;
      }
      out << '\n';
    }
  }
  if (!out) throw std::runtime_error("cannot write the verdicts");
}

}  // namespace orbit
