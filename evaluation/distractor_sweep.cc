#include "evaluation/distractor_sweep.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>
#include <string>

#include "evaluation/evaluation_plot.h"
#include "evaluation/evaluation_report.h"

namespace orbit {
namespace {

// Throws std::invalid_argument unless the reports are one sweep (the header's contract).
void RequireOneSweep(const std::vector<EvaluationReport>& reports) {
  if (reports.empty()) throw std::invalid_argument("a distractor sweep needs at least one report");
  for (const EvaluationReport& report : reports) {
    bool same = report.cells.size() == reports.front().cells.size();
    for (std::size_t c = 0; same && c < report.cells.size(); ++c) {
      const EvaluationCell& a = report.cells[c];
      const EvaluationCell& b = reports.front().cells[c];
      same = a.method == b.method && a.variant == b.variant && a.distortion == b.distortion &&
             a.n == b.n;
    }
    if (!same) {
      throw std::invalid_argument("the reports of " + std::to_string(report.distractors) + " and " +
                                  std::to_string(reports.front().distractors) +
                                  " distractors do not have the same cells");
    }
  }
}

bool HasUnknowns(const std::vector<EvaluationReport>& reports) {
  for (const EvaluationCell& cell : reports.front().cells) {
    if (cell.unknown_trials > 0) return true;
  }
  return false;
}

std::string Percent(double rate) { return Format("%.1f", 100 * rate); }

}  // namespace

std::string DistractorSweepMarkdown(const std::vector<EvaluationReport>& reports) {
  RequireOneSweep(reports);
  const bool unknowns = HasUnknowns(reports);
  std::ostringstream out;
  const std::vector<EvaluationCell>& cells = reports.front().cells;
  for (std::size_t first = 0; first < cells.size();) {
    const DescriptorVariant variant = cells[first].variant;
    out << "### " << VariantName(variant) << ": against the number of distractors, hit rate (%)"
        << (unknowns ? " and unknown objects rejected (%)" : "")
        << "\n\n| distortion | method | n |";
    for (const EvaluationReport& report : reports) out << " hits, " << report.distractors << " |";
    if (unknowns) {
      for (const EvaluationReport& report : reports) {
        out << " unknowns, " << report.distractors << " |";
      }
    }
    out << "\n|---|---|---:|";
    for (std::size_t k = 0; k < reports.size() * (unknowns ? 2 : 1); ++k) out << "---:|";
    out << "\n";
    std::size_t c = first;
    for (; c < cells.size() && cells[c].variant == variant; ++c) {
      out << "| " << cells[c].distortion << " | " << cells[c].method << " | " << cells[c].n << " |";
      for (const EvaluationReport& report : reports) {
        out << " " << Percent(report.cells[c].hit_rate()) << " |";
      }
      if (unknowns) {
        for (const EvaluationReport& report : reports) {
          out << " " << Percent(report.cells[c].reject_rate()) << " |";
        }
      }
      out << "\n";
    }
    out << "\n";
    first = c;
  }
  return out.str();
}

void WriteDistractorSweepCsv(const std::vector<EvaluationReport>& reports, std::ostream& out) {
  RequireOneSweep(reports);
  out << "distractors,method,variant,distortion,n,trials,hits,hit_rate,unknown_trials,rejected,"
         "reject_rate\n";
  for (const EvaluationReport& report : reports) {
    for (const EvaluationCell& cell : report.cells) {
      out << report.distractors << "," << cell.method << "," << VariantName(cell.variant) << ","
          << cell.distortion << "," << cell.n << "," << cell.trials << "," << cell.hits << ","
          << Format("%.4f", cell.hit_rate()) << "," << cell.unknown_trials << "," << cell.rejected
          << "," << Format("%.4f", cell.reject_rate()) << "\n";
    }
  }
}

cv::Mat DrawDistractorSweepPlot(const std::vector<EvaluationReport>& reports) {
  RequireOneSweep(reports);
  const bool unknowns = HasUnknowns(reports);
  const std::vector<EvaluationCell>& cells = reports.front().cells;
  LineFigure figure;
  figure.title = "Among distractors: top-1 hit rate" +
                 std::string(unknowns ? " and unknown objects rejected" : "") + " (seed " +
                 std::to_string(reports.front().seed) + ")";
  std::vector<std::string> distortions;
  for (const EvaluationCell& cell : cells) {
    if (std::find(distortions.begin(), distortions.end(), cell.distortion) == distortions.end()) {
      distortions.push_back(cell.distortion);
    }
  }
  figure.columns = static_cast<int>(distortions.size());
  for (std::size_t c = 0; c < cells.size(); ++c) {
    const std::string title =
        std::string(VariantName(cells[c].variant)) + ", " + cells[c].distortion;
    if (figure.panels.empty() || figure.panels.back().title != title) {
      LinePanel& panel = figure.panels.emplace_back();
      panel.title = title;
      panel.x_label = "distractor objects";
      panel.y_label = unknowns ? "hits / unknowns rejected (%)" : "hit rate (%)";
      for (std::size_t k = 0; k < reports.size(); ++k) {
        panel.ticks.emplace_back(static_cast<double>(k), std::to_string(reports[k].distractors));
      }
    }
    LinePanel& panel = figure.panels.back();
    const std::string name = cells[c].method + ", n = " + std::to_string(cells[c].n);
    LineSeries& hits = panel.series.emplace_back();
    hits.name = name + ": hits";
    for (std::size_t k = 0; k < reports.size(); ++k) {
      hits.points.emplace_back(static_cast<double>(k), reports[k].cells[c].hit_rate());
    }
    if (!unknowns) continue;
    LineSeries& rejected = panel.series.emplace_back();
    rejected.name = name + ": unknowns rejected";
    for (std::size_t k = 0; k < reports.size(); ++k) {
      rejected.points.emplace_back(static_cast<double>(k), reports[k].cells[c].reject_rate());
    }
  }
  return DrawLineFigure(figure);
}

}  // namespace orbit
