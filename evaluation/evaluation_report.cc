#include "evaluation/evaluation_report.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <sstream>
#include <string_view>
#include <vector>

#include "core/engines/product_pipeline.h"

namespace orbit {

std::string Format(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

namespace {

std::string Mebibytes(std::size_t bytes) { return Format("%.2f MiB", bytes / 1048576.0); }

// A cell of the tables: `value` formatted, or "-" when the cell counted no query (an n longer
// than every captured sequence), as the recognition tables write a share of nothing.
std::string CellText(const char* format, double value, int queries) {
  return queries > 0 ? Format(format, value) : "-";
}

// The report's cells of one variant, in the report's order (distortion, method, n).
std::vector<const EvaluationCell*> CellsOf(const EvaluationReport& report,
                                           DescriptorVariant variant) {
  std::vector<const EvaluationCell*> cells;
  for (const EvaluationCell& cell : report.cells) {
    if (cell.variant == variant) cells.push_back(&cell);
  }
  return cells;
}

// The distinct variants of the report's cells, in the order they first appear.
std::vector<DescriptorVariant> VariantsOf(const EvaluationReport& report) {
  std::vector<DescriptorVariant> variants;
  for (const EvaluationCell& cell : report.cells) {
    if (std::find(variants.begin(), variants.end(), cell.variant) == variants.end()) {
      variants.push_back(cell.variant);
    }
  }
  return variants;
}

// "1 unknown object", "2 unknown objects".
std::string Objects(int count, const std::string& kind) {
  return std::to_string(count) + " " + kind + (count == 1 ? " object" : " objects");
}

// The first line of the report: what was evaluated, on what, and how long it took.
std::string RunLine(const EvaluationReport& report) {
  std::ostringstream out;
  if (report.server) {
    const ServerDescription& server = *report.server;
    out << "Server " << server.address << " (orbit " << server.version
        << "): " << Objects(report.known_objects, "enrolled") << ", " << server.views << " views";
    if (report.unknown_objects > 0) {
      out << "; " << Objects(report.unknown_objects, "unknown") << " among the queries";
    }
    out << "; sessions " << Format("%.1f", report.trial_seconds) << " s.\n\n";
    return out.str();
  }
  out << "Seed " << report.seed << "; " << Objects(report.known_objects, "known");
  if (report.unknown_objects > 0) out << ", " << Objects(report.unknown_objects, "unknown");
  if (report.distractors > 0) {
    out << ", " << report.distractors << " distractor objects "
        << (report.distractors_from.empty() ? "generated" : "from " + report.distractors_from)
        << " in the model set";
  }
  out << ", " << report.images << " images; index "
      << (report.search == SearchMode::kExact ? "exact" : "kdtree") << "; " << report.threads
      << " threads; descriptors " << Format("%.1f", report.descriptor_seconds) << " s, trials "
      << Format("%.1f", report.trial_seconds) << " s.\n\n";
  return out.str();
}

// The distinct n values in the report, in the order they first appear.
std::vector<int> QueryLengths(const EvaluationReport& report) {
  std::vector<int> ns;
  for (const EvaluationCell& cell : report.cells) {
    if (std::find(ns.begin(), ns.end(), cell.n) == ns.end()) ns.push_back(cell.n);
  }
  return ns;
}

// Rows of a table: consecutive cells sharing distortion and method (one cell per n).
template <typename WriteRow>
void ForEachRow(const std::vector<const EvaluationCell*>& cells, std::size_t n_count,
                WriteRow write_row) {
  for (std::size_t first = 0; first + n_count <= cells.size(); first += n_count) {
    write_row(
        std::vector<const EvaluationCell*>(cells.begin() + first, cells.begin() + first + n_count));
  }
}

}  // namespace

std::string DistortionLabel(const std::string& distortion) {
  // The protocol's three are the only names without parameters: DF, MB, GN as in the thesis.
  if (distortion.find(':') != std::string::npos) return distortion;
  std::string label = distortion;
  for (char& c : label) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return label;
}

std::string MarkdownReport(const EvaluationReport& report) {
  std::ostringstream out;
  const std::vector<int> ns = QueryLengths(report);
  const bool recognition = report.unknown_objects > 0;
  out << RunLine(report);
  if (report.query_sequences > 0) {
    out << "Queries: " << report.query_sequences << " captured sequences, " << report.query_frames
        << " frames (`--queries`), "
        << (report.server ? "each streamed as one session with the server's defaults, read "
                            "after its n-th frame, against the server's enrolled objects"
                          : "against every image of the model set")
        << "; a sequence shorter than n is not counted at n (\"-\": none is that long).\n\n";
  }
  // The engines' options, orientation, active vision and index: one line, each part only when
  // something it describes ran. The product runs its own options (DescribeProduct below), so
  // the thesis' engine options are stated only when one of those engines ran.
  std::ostringstream setup;
  const bool thesis_engines =
      !report.server &&
      std::any_of(report.cells.begin(), report.cells.end(),
                  [](const EvaluationCell& cell) { return cell.method != kProductMethod; });
  const EngineOptions& e = report.engine;
  if (thesis_engines) {
    setup << " Engines: window " << e.window << ", N_L " << e.list_length << ", w "
          << Format("%g", e.orientation_weight) << ", HMM states " << e.hmm_states << ", Th "
          << Format("%g", e.threshold) << ".";
  }
  if (!report.use_orientation) {
    setup << " Orientation ignored: the query frames carry no azimuth (`--orientation ignore`).";
  }
  if (report.active_step > 0) {
    setup << " Active vision (`--active`): after the first two views, each next view "
          << Format("%g", report.active_step) << [&] {
               switch (report.active_policy) {
                 case ActivePolicy::kFollowMoves:
                   return " degrees from the latest in the direction the method suggested.";
                 case ActivePolicy::kOneWay:
                   return " degrees on from the latest, always the same way (the suggestion "
                          "ignored).";
                 case ActivePolicy::kBestOfBoth:
                   return " degrees from the latest, both ways at every step, keeping the path "
                          "best for the truth (the bound of any left / right suggestion).";
               }
               return "";
             }();
  }
  if (report.search == SearchMode::kKdTree) {
    setup << " kd-tree: " << report.index.kd_trees << " trees, " << report.index.kd_checks
          << " checks, " << report.index.kd_candidates << " candidates re-ranked.";
  }
  if (!setup.str().empty()) out << setup.str().substr(1) << "\n\n";
  if (report.server) {
    const ServerDescription& server = *report.server;
    out << (report.cells.empty() ? std::string("server") : report.cells.front().method)
        << ": the server's session defaults, " << server.defaults;
    if (server.runs_product) out << ": the product pipeline, " << DescribeProduct();
    out << ". ms/query: the server's processing time of a query's frames, as its updates "
           "state it.\n";
  } else if (std::any_of(report.cells.begin(), report.cells.end(), [](const EvaluationCell& cell) {
               return cell.method == kProductMethod;
             })) {
    out << "product: what `orbit serve` runs by default, " << DescribeProduct();
    if (std::any_of(report.cells.begin(), report.cells.end(), [](const EvaluationCell& cell) {
          return cell.method == kProductMethod && cell.variant != Product().variant;
        })) {
      out << "; under another variant, the same pipeline on a store made in that variant "
             "(`orbit serve --variant`), at that variant's target false-accept rate unless "
             "the run gives one ("
          << DescribeProductFalseAcceptRates() << ")";
    }
    out << ".\n\n";
  }
  // Only the variants some method ran on: the runner also describes and indexes a variant
  // that is listed but evaluated by no method (a CEDD-only --variant beside --methods product
  // alone).
  for (const ModelMemory& memory : report.memory) {
    if (CellsOf(report, memory.variant).empty()) continue;
    out << "Model memory (" << VariantName(memory.variant) << "): " << memory.objects
        << " objects, " << memory.views << " views, descriptors "
        << Mebibytes(memory.descriptor_bytes) << ", index " << Mebibytes(memory.index_bytes)
        << " (heap held by the built index).\n";
  }

  for (const DescriptorVariant variant : VariantsOf(report)) {
    const auto cells = CellsOf(report, variant);
    // Captured sequences shorter than a cell's n are not counted in it: cells can differ.
    int fewest = cells.front()->trials, most = fewest;
    for (const EvaluationCell* cell : cells) {
      fewest = std::min(fewest, cell->trials);
      most = std::max(most, cell->trials);
    }
    out << "\n### " << VariantName(variant) << ": hit rate (%), top-1, "
        << (fewest == most ? std::to_string(most)
                           : std::to_string(fewest) + "-" + std::to_string(most))
        << " queries per cell\n\n| distortion | method |";
    for (int n : ns) out << " n=" << n << " |";
    out << " ms/query (n=" << ns.back() << ") |\n|---|---|";
    for (std::size_t i = 0; i <= ns.size(); ++i) out << "---:|";
    out << "\n";
    ForEachRow(cells, ns.size(), [&](const std::vector<const EvaluationCell*>& row) {
      out << "| " << DistortionLabel(row.front()->distortion) << " | " << row.front()->method
          << " |";
      for (const EvaluationCell* cell : row)
        out << " " << CellText("%.1f", 100 * cell->hit_rate(), cell->trials) << " |";
      const EvaluationCell& last = *row.back();
      out << " " << CellText("%.3f", last.ms_per_query(), last.trials + last.unknown_trials)
          << " |\n";
    });

    if (!recognition) continue;
    out << "\n### " << VariantName(variant)
        << ": recognition (%), known objects right and accepted / unknown objects rejected\n\n"
           "| distortion | method |";
    for (int n : ns) out << " n=" << n << " |";
    out << "\n|---|---|";
    for (std::size_t i = 0; i < ns.size(); ++i) out << "---:|";
    out << "\n";
    ForEachRow(cells, ns.size(), [&](const std::vector<const EvaluationCell*>& row) {
      out << "| " << DistortionLabel(row.front()->distortion) << " | " << row.front()->method
          << " |";
      for (const EvaluationCell* cell : row) {
        out << " " << CellText("%.1f", 100 * cell->accept_rate(), cell->trials) << " / "
            << CellText("%.1f", 100 * cell->reject_rate(), cell->unknown_trials) << " |";
      }
      out << "\n";
    });
  }
  return out.str();
}

void WriteCsv(const EvaluationReport& report, std::ostream& out) {
  const bool recognition = report.unknown_objects > 0;
  out << "method,variant,distortion,n,trials,hits,hit_rate,ms_per_query";
  if (recognition) out << ",accepted,accept_rate,unknown_trials,rejected,reject_rate";
  out << "\n";
  for (const EvaluationCell& cell : report.cells) {
    out << cell.method << ',' << VariantName(cell.variant) << ',' << cell.distortion << ','
        << cell.n << ',' << cell.trials << ',' << cell.hits << ','
        << Format("%.4f", cell.hit_rate()) << ',' << Format("%.4f", cell.ms_per_query());
    if (recognition) {
      out << ',' << cell.accepted << ',' << Format("%.4f", cell.accept_rate()) << ','
          << cell.unknown_trials << ',' << cell.rejected << ','
          << Format("%.4f", cell.reject_rate());
    }
    out << "\n";
  }
}

}  // namespace orbit
