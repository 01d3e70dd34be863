#include "evaluation/distortion_sweep.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "evaluation/evaluation_plot.h"

namespace orbit {
namespace {

struct Axis {
  const char* name;
  const char* strength;
  double from, to;         // the default range
  double lowest, highest;  // what the distortion accepts
  bool whole;              // strengths rounded to whole numbers
};

constexpr Axis kAxes[] = {
    {"mb", "blur length (px)", 5, 25, 1, 200, false},
    {"gn", "noise variance", 0.002, 0.03, 0, 1, false},
    {"jpeg", "JPEG quality", 10, 60, 1, 100, true},
    {"gain", "gain", 0.6, 1.4, 0.01, 10, false},
};

[[noreturn]] void Fail(std::string_view text, const std::string& why) {
  throw std::invalid_argument("\"" + std::string(text) + "\": " + why);
}

double Number(std::string_view text, std::string_view whole) {
  const std::string s(text);
  char* end = nullptr;
  const double value = std::strtod(s.c_str(), &end);
  if (s.empty() || end != s.c_str() + s.size() || !std::isfinite(value)) {
    Fail(whole, "\"" + s + "\" is not a number");
  }
  return value;
}

std::string Compact(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

// The spec text of `axis` at strength `value`, step `step`.
std::string SpecText(const Axis& axis, double value, int step) {
  const std::string a(axis.name);
  if (a == "mb") {
    return "mb:len=" + Compact(value) + ":angle=" + std::to_string(step * 37 % 180);
  }
  if (a == "gn") return "gn:var=" + Compact(value);
  if (a == "jpeg") return "jpeg:q=" + Compact(value);
  return "gain:" + Compact(value);
}

const DistortionSweep* SweepOf(const std::vector<DistortionSweep>& sweeps,
                               const std::string& distortion, std::size_t* step) {
  for (const DistortionSweep& sweep : sweeps) {
    for (std::size_t s = 0; s < sweep.distortions.size(); ++s) {
      if (sweep.distortions[s].name == distortion) {
        *step = s;
        return &sweep;
      }
    }
  }
  return nullptr;
}

std::string SeriesName(const EvaluationCell& cell) {
  return cell.method + " (" + std::string(VariantName(cell.variant)) + ")";
}

// Per sweep: (series, n) -> hit rate per step, in the order series and n first appear.
using SweepRows =
    std::vector<std::pair<std::pair<std::string, int>, std::vector<const EvaluationCell*>>>;

SweepRows RowsOf(const EvaluationReport& report, const std::vector<DistortionSweep>& sweeps,
                 const DistortionSweep& sweep) {
  SweepRows rows;
  for (const EvaluationCell& cell : report.cells) {
    std::size_t step = 0;
    if (SweepOf(sweeps, cell.distortion, &step) != &sweep) continue;
    const std::pair<std::string, int> key{SeriesName(cell), cell.n};
    auto row =
        std::find_if(rows.begin(), rows.end(), [&](const auto& r) { return r.first == key; });
    if (row == rows.end()) {
      rows.push_back({key, std::vector<const EvaluationCell*>(sweep.distortions.size(), nullptr)});
      row = rows.end() - 1;
    }
    row->second[step] = &cell;
  }
  return rows;
}

}  // namespace

DistortionSweep ParseSweep(std::string_view text, int steps) {
  if (steps < kMinSweepSteps || steps > kMaxSweepSteps) {
    Fail(text, "steps must be in " + std::to_string(kMinSweepSteps) + ".." +
                   std::to_string(kMaxSweepSteps) + ", got " + std::to_string(steps));
  }
  const std::size_t colon = text.find(':');
  const std::string_view name = text.substr(0, colon);
  const Axis* axis = nullptr;
  for (const Axis& a : kAxes) {
    if (name == a.name) axis = &a;
  }
  if (axis == nullptr)
    Fail(text, "unknown axis \"" + std::string(name) + "\" (mb, gn, jpeg, gain)");
  double from = axis->from, to = axis->to;
  if (colon != std::string_view::npos) {
    const std::string_view range = text.substr(colon + 1);
    const std::size_t dots = range.find("..");
    if (dots == std::string_view::npos) Fail(text, "the range must read FROM..TO");
    from = Number(range.substr(0, dots), text);
    to = Number(range.substr(dots + 2), text);
    if (!(from < to)) Fail(text, "FROM must be below TO");
    if (from < axis->lowest || to > axis->highest) {
      Fail(text, std::string(axis->strength) + " must be in " + Compact(axis->lowest) + ".." +
                     Compact(axis->highest));
    }
  }
  DistortionSweep sweep;
  sweep.axis = axis->name;
  sweep.strength = axis->strength;
  for (int k = 0; k < steps; ++k) {
    double value = from + (to - from) * k / (steps - 1);
    value = axis->whole ? std::round(value) : std::round(value * 1e6) / 1e6;
    if (!sweep.strengths.empty() && value == sweep.strengths.back()) continue;
    sweep.strengths.push_back(value);
    sweep.distortions.push_back(ParseDistortionSpec(SpecText(*axis, value, k)));
  }
  return sweep;
}

std::string SweepMarkdown(const EvaluationReport& report,
                          const std::vector<DistortionSweep>& sweeps) {
  std::ostringstream out;
  for (const DistortionSweep& sweep : sweeps) {
    out << "### Sweep: " << sweep.strength << " (hit rate %, top-1)\n\n| method | n |";
    for (std::size_t s = 0; s < sweep.strengths.size(); ++s) {
      out << " "
          << (sweep.axis == "mb" ? sweep.distortions[s].name.substr(3)
                                 : Compact(sweep.strengths[s]))
          << " |";
    }
    out << " worst |\n|---|---:|";
    for (std::size_t s = 0; s <= sweep.strengths.size(); ++s) out << "---:|";
    out << "\n";
    for (const auto& [key, cells] : RowsOf(report, sweeps, sweep)) {
      out << "| " << key.first << " | " << key.second << " |";
      double worst = 1;
      for (const EvaluationCell* cell : cells) {
        if (cell == nullptr) {
          out << " |";
          continue;
        }
        worst = std::min(worst, cell->hit_rate());
        char value[16];
        std::snprintf(value, sizeof value, "%.1f", 100 * cell->hit_rate());
        out << " " << value << " |";
      }
      char value[16];
      std::snprintf(value, sizeof value, "%.1f", 100 * worst);
      out << " " << value << " |\n";
    }
    out << "\n";
  }
  return out.str();
}

void WriteSweepCsv(const EvaluationReport& report, const std::vector<DistortionSweep>& sweeps,
                   std::ostream& out) {
  out << "axis,strength,distortion,method,variant,n,trials,hits,hit_rate\n";
  for (const EvaluationCell& cell : report.cells) {
    std::size_t step = 0;
    const DistortionSweep* sweep = SweepOf(sweeps, cell.distortion, &step);
    if (sweep == nullptr) continue;
    char rate[16];
    std::snprintf(rate, sizeof rate, "%.4f", cell.hit_rate());
    out << sweep->axis << "," << Compact(sweep->strengths[step]) << "," << cell.distortion << ","
        << cell.method << "," << VariantName(cell.variant) << "," << cell.n << "," << cell.trials
        << "," << cell.hits << "," << rate << "\n";
  }
}

cv::Mat DrawSweepPlot(const EvaluationReport& report, const std::vector<DistortionSweep>& sweeps) {
  std::vector<int> ns;
  for (const EvaluationCell& cell : report.cells) {
    if (std::find(ns.begin(), ns.end(), cell.n) == ns.end()) ns.push_back(cell.n);
  }
  std::sort(ns.begin(), ns.end());
  LineFigure figure;
  figure.title = "Top-1 hit rate vs distortion strength (" +
                 std::to_string(report.cells.empty() ? 0 : report.cells.front().trials) +
                 " queries per point, seed " + std::to_string(report.seed) + ")";
  figure.columns = static_cast<int>(sweeps.size());
  for (const int n : ns) {
    for (const DistortionSweep& sweep : sweeps) {
      LinePanel& panel = figure.panels.emplace_back();
      panel.title = sweep.strength + ", n = " + std::to_string(n);
      panel.x_label = sweep.strength;
      for (double s : sweep.strengths) panel.ticks.emplace_back(s, Compact(s));
      for (const auto& [key, cells] : RowsOf(report, sweeps, sweep)) {
        if (key.second != n) continue;
        LineSeries& line = panel.series.emplace_back();
        line.name = key.first;
        for (std::size_t s = 0; s < cells.size(); ++s) {
          if (cells[s] != nullptr)
            line.points.emplace_back(sweep.strengths[s], cells[s]->hit_rate());
        }
      }
    }
  }
  return DrawLineFigure(figure);
}

}  // namespace orbit
