// Writing an EvaluationReport (evaluation/evaluation_runner.h) for people and for programs: the
// Markdown tables `orbit eval` prints and the CSV file of --csv.
//
// All functions are thread-safe (they only read the report).
#pragma once

#include <ostream>
#include <string>

#include "evaluation/evaluation_runner.h"

namespace orbit {

// `value` written with `format`, one printf conversion of a double (at most 63 characters).
std::string Format(const char* format, double value);

// The distortion as the thesis and the tables write it: "DF", "MB", "GN".
std::string DistortionLabel(const std::string& distortion);

// The report as Markdown: a line with the run's parameters (seed, objects, index, threads,
// times; for a server's report, the server, its objects and the sessions' time instead), the
// thesis' engine options when one of those engines ran locally, the model memory of each
// variant a method ran on (none for a server's report: the server's memory is not measured
// here; its session defaults instead), then per variant a table of hit rates in percent with one
// row per distortion x method and one column per n, plus the time per query at the largest n. When
// unknown objects were queried, a second table per variant gives, per n, the percentage of
// known-object queries answered right and accepted, and of unknown-object queries rejected. A
// cell that counted no query (an n longer than every captured sequence) reads "-".
std::string MarkdownReport(const EvaluationReport& report);

// The report as CSV, one row per cell, header
//   method,variant,distortion,n,trials,hits,hit_rate,ms_per_query
// (hit_rate = hits / trials in [0, 1], 4 decimals; ms_per_query 4 decimals), and, when unknown
// objects were queried, the extra columns accepted,accept_rate,unknown_trials,rejected,reject_rate.
void WriteCsv(const EvaluationReport& report, std::ostream& out);

}  // namespace orbit
