// orbit eval: the evaluation protocol (docs/design.md#evaluation-protocol) on a dataset
// (evaluation/evaluation_runner.h), or a user's captured query sequences recognised against a
// local model set or, with --server, by a running server (evaluation/server_evaluation.h): a
// Markdown table of hit rates on stdout, optionally a CSV file and a PNG plot.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "cli/box_arguments.h"
#include "cli/commands.h"
#include "cli/network_options.h"
#include "cli/progress_bar.h"
#include "client/connection.h"
#include "client/rpc_error.h"
#include "core/engines/product_pipeline.h"
#include "evaluation/dataset.h"
#include "evaluation/distortion_sweep.h"
#include "evaluation/distractor_objects.h"
#include "evaluation/distractor_sweep.h"
#include "evaluation/evaluation_plot.h"
#include "evaluation/evaluation_report.h"
#include "evaluation/evaluation_runner.h"
#include "evaluation/recognition_report.h"
#include "evaluation/server_evaluation.h"
#include "storage/sqlite_model_store.h"

namespace orbit::cli {
namespace {

// Names of `values` as the command line writes them.
template <typename T, typename NameOf>
std::vector<std::string> Names(const std::vector<T>& values, NameOf name_of) {
  std::vector<std::string> names;
  for (const T& value : values) names.emplace_back(name_of(value));
  return names;
}

// How every CSV file of the command names its images (evaluation/dataset.h, ReadManifest).
constexpr std::string_view kRelativePathsHelp =
    "a relative path in it is read from the CSV file's own folder, not the working directory";

// The command's options; every default is the harness's own (EvaluationOptions,
// ViewIndexOptions, EngineOptions), never typed again here.
struct EvalOptions {
  std::string layout;  // "": manifest when --manifest is given, else coil100 (SelectDataset)
  std::string data;
  std::string manifest;
  std::string boxes;                      // boxes.csv: describe each image's object region
  double box_margin = kDefaultBoxMargin;  // share of the box's size added on each side
  std::vector<std::string> methods = EvaluationOptions{}.methods;
  std::vector<std::string> variants = Names(EvaluationOptions{}.variants, VariantName);
  std::vector<std::string> distortions =
      Names(EvaluationOptions{}.distortions, [](const DistortionSpec& d) { return d.name; });
  std::string queries;              // --queries: captured query sequences (CSV)
  std::vector<std::string> sweeps;  // --sweep: axes whose strength is swept
  int sweep_steps = 6;
  std::vector<int> ns = EvaluationOptions{}.query_lengths;
  int trials = EvaluationOptions{}.trials;
  std::uint64_t seed = EvaluationOptions{}.seed;
  std::string orientation = EvaluationOptions{}.use_orientation ? "use" : "ignore";
  std::string quality_reading = EvaluationOptions{}.use_quality_reading ? "use" : "ignore";
  std::string objects;
  std::string unknown_objects;
  std::string index = "exact";
  int kd_trees = ViewIndexOptions{}.kd_trees;
  int kd_checks = ViewIndexOptions{}.kd_checks;
  int kd_candidates = ViewIndexOptions{}.kd_candidates;
  double threshold = EngineOptions{}.threshold;
  std::string rejection = std::string(RejectionRuleName(EngineOptions{}.rejection));
  std::optional<double> false_accept_rate;  // unset: the engines' default, the product's variant's
  double known_accept_rate = EngineOptions{}.known_accept_rate;
  std::string verdicts;
  bool active = false;
  double active_step = 20;
  std::string active_policy{ActivePolicyName(ActivePolicy::kFollowMoves)};
  std::string recognition_plot;
  double orientation_weight = EngineOptions{}.orientation_weight;
  int list_length = EngineOptions{}.list_length;
  int hmm_states = EngineOptions{}.hmm_states;
  int hmm_sharpness = EngineOptions{}.hmm_sharpness;
  double nearest_view_weight = EngineOptions{}.nearest_view_weight;
  int candidates = 0;
  int candidates_above = 0;
  // --distractors: empty for none (or, with --distractors-from, all of the store's); several
  // counts run the evaluation once per count (a distractor sweep).
  std::vector<int> distractors;
  std::string distractors_from;  // --distractors-from: a model store (SQLite file)
  std::string csv;
  std::string plot;
  int threads = EvaluationOptions{}.threads;
  bool no_progress = false;
  NetworkOptions network;  // --server: the queries go to a running server
};

std::vector<DistortionSweep> Sweeps(const EvalOptions& o) {
  std::vector<DistortionSweep> sweeps;
  for (const std::string& text : o.sweeps) sweeps.push_back(ParseSweep(text, o.sweep_steps));
  return sweeps;
}

EvaluationOptions ToEvaluationOptions(const EvalOptions& o) {
  EvaluationOptions options;
  options.variants.clear();
  for (const std::string& name : o.variants) options.variants.push_back(*ParseVariant(name));
  options.methods = o.methods;
  options.distortions.clear();
  for (const std::string& name : o.distortions)
    options.distortions.push_back(ParseDistortionSpec(name));
  for (const DistortionSweep& sweep : Sweeps(o)) {
    options.distortions.insert(options.distortions.end(), sweep.distortions.begin(),
                               sweep.distortions.end());
  }
  options.query_lengths = o.ns;
  options.trials = o.trials;
  options.seed = o.seed;
  options.use_orientation = o.orientation == "use";
  options.use_quality_reading = o.quality_reading == "use";
  options.index.search = o.index == "kdtree" ? SearchMode::kKdTree : SearchMode::kExact;
  options.index.kd_trees = o.kd_trees;
  options.index.kd_checks = o.kd_checks;
  options.index.kd_candidates = o.kd_candidates;
  options.engine.threshold = o.threshold;
  options.engine.rejection = ParseRejectionRule(o.rejection);
  options.active_step = o.active ? o.active_step : 0;
  options.active_policy = *ParseActivePolicy(o.active_policy);
  options.engine.false_accept_rate =
      o.false_accept_rate.value_or(EngineOptions{}.false_accept_rate);
  options.product_false_accept_rate = o.false_accept_rate;
  options.engine.known_accept_rate = o.known_accept_rate;
  options.engine.orientation_weight = o.orientation_weight;
  options.engine.list_length = o.list_length;
  options.engine.hmm_states = o.hmm_states;
  options.engine.hmm_sharpness = o.hmm_sharpness;
  options.engine.nearest_view_weight = o.nearest_view_weight;
  options.engine.candidate_objects = o.candidates;
  options.engine.candidates_above = o.candidates_above;
  options.threads = o.threads;
  return options;
}

// Prints the report and writes the files the options ask for; the one output of both modes.
void WriteReport(const EvaluationReport& report, const EvalOptions& o) {
  const std::vector<DistortionSweep> sweeps = Sweeps(o);
  std::cout << MarkdownReport(report);
  if (!sweeps.empty()) std::cout << SweepMarkdown(report, sweeps);
  if (report.unknown_objects > 0 || !o.verdicts.empty()) {
    std::cout << RecognitionMarkdown(report) << SeparationMarkdown(report)
              << ReliabilityMarkdown(report);
  }
  std::cout << std::flush;
  if (!o.csv.empty()) {
    std::ofstream csv(o.csv);
    if (csv) sweeps.empty() ? WriteCsv(report, csv) : WriteSweepCsv(report, sweeps, csv);
    if (!csv) throw std::runtime_error(o.csv + ": cannot write the CSV file");
  }
  if (!o.recognition_plot.empty()) {
    WritePng(DrawLineFigure(RecognitionCurves(report)), o.recognition_plot);
  }
  if (!o.verdicts.empty()) {
    std::ofstream verdicts(o.verdicts);
    if (!verdicts) throw std::runtime_error(o.verdicts + ": cannot write the verdicts file");
    WriteVerdictsCsv(report, verdicts);
  }
  if (!o.plot.empty()) {
    if (sweeps.empty()) {
      WriteHitRatePlot(report, o.plot);
    } else {
      WritePng(DrawSweepPlot(report, sweeps), o.plot);
    }
  }
}

// The flags a local evaluation takes that mean nothing with --server, and why. A flag listed
// neither here nor in kServerFlags is refused too, for setting up a local evaluation.
const std::map<std::string, std::string>& ServerRefusalReasons() {
  static const std::map<std::string, std::string> reasons = [] {
    std::map<std::string, std::string> r;
    for (const char* flag : {"--layout", "--data", "--manifest", "--objects"}) {
      r[flag] = "the model set is the objects the server holds";
    }
    r["--unknown-objects"] =
        "a query of an object the server does not hold is an unknown query already";
    for (const char* flag :
         {"--methods", "--variant", "--index", "--kd-trees", "--kd-checks", "--kd-candidates",
          "--threshold", "--rejection", "--false-accept-rate", "--known-accept-rate",
          "--orientation-weight", "--list-length", "--hmm-states", "--hmm-sharpness",
          "--nearest-view-weight", "--candidates", "--candidates-above", "--distractors",
          "--distractors-from"}) {
      r[flag] = "the server recognises with its own variant, engine and session defaults";
    }
    for (const char* flag : {"--distortions", "--sweep", "--sweep-steps"}) {
      r[flag] = "the server is sent the frames as captured (df)";
    }
    for (const char* flag : {"--active", "--active-step", "--active-policy"}) {
      r[flag] = "captured sequences have their views already";
    }
    for (const char* flag : {"--trials", "--seed", "--threads"}) {
      r[flag] = "each captured sequence is one query, streamed once as one session";
    }
    r["--quality-reading"] =
        "the client library sends every frame's quality reading, as a device does";
    r["--recognition-plot"] = "a server's updates do not state the p-values its curves need";
    return r;
  }();
  return reasons;
}

// What --server works with: the network flags, the queries and how they are sent and reported.
constexpr std::string_view kServerFlags[] = {
    "--server",   "--token", "--token-file",  "--tls-ca",     "--tls-server-name", "--timeout",
    "--queries",  "--n",     "--boxes",       "--box-margin", "--orientation",     "--csv",
    "--verdicts", "--plot",  "--no-progress", "--help"};

// Throws std::invalid_argument naming the first flag given on `command` that does not apply
// with --server, and when --queries is missing. --distortions df alone is accepted: it is
// what the server is sent.
void RefuseLocalFlags(const CLI::App& command, const EvalOptions& o) {
  if (o.queries.empty()) {
    throw std::invalid_argument(
        "--server needs --queries FILE: the captured query sequences to send it, a CSV with "
        "columns path,object,sequence[,azimuth]");
  }
  for (const CLI::Option* option : command.get_options()) {
    if (option->count() == 0) continue;
    const std::string name = option->get_name();
    if (std::find(std::begin(kServerFlags), std::end(kServerFlags), name) !=
        std::end(kServerFlags)) {
      continue;
    }
    if (name == "--distortions" && o.distortions == std::vector<std::string>{"df"}) continue;
    const auto& reasons = ServerRefusalReasons();
    const auto found = reasons.find(name);
    throw std::invalid_argument(
        name + " does not apply with --server: " +
        (found != reasons.end() ? found->second : "it sets up a local evaluation"));
  }
}

// `orbit eval --server --queries`: the captures streamed to the server, one session each.
int RunServerEval(const EvalOptions& o) {
  try {
    const std::vector<CaptureFrame> captures = ReadQueryCaptures(o.queries);
    ServerEvaluationOptions options;
    options.query_lengths = o.ns;
    options.use_orientation = o.orientation == "use";
    if (!o.boxes.empty()) options.boxes = ReadBoxes(o.boxes);
    options.box_margin = o.box_margin;
    std::unique_ptr<ProgressBar> progress;
    if (!o.no_progress) {
      progress = std::make_unique<ProgressBar>(std::cerr, ::isatty(STDERR_FILENO) == 1);
      options.progress = [&progress](std::string_view stage, std::size_t done, std::size_t total) {
        progress->Update(stage, done, total);
      };
    }
    const Connection connection(ToConnectionOptions(o.network));
    const EvaluationReport report = RunServerEvaluation(connection, captures, options);
    progress.reset();
    WriteReport(report, o);
    return 0;
  } catch (const RpcError&) {
    throw;  // main() says which server could not be reached, or what it refused
  } catch (const std::exception& e) {
    std::cerr << "orbit eval: " << e.what() << "\n";
    return 1;
  }
}

// The objects of the store `file`. Throws StoreError as the store's constructor.
std::size_t ObjectsHeld(const std::string& file) {
  std::size_t held = 0;
  {
    SqliteModelStore store(file);
    ListRequest request{.after_id = 0, .limit = kMaxListLimit};
    for (std::vector<ObjectSummary> page; !(page = store.List(request)).empty();) {
      held += page.size();
      request.after_id = page.back().id;
    }
  }
  return held;
}

// The distractor counts the options ask for, one evaluation each: --distractors as given, or
// with --distractors-from and no --distractors every object of the store. Throws
// std::invalid_argument when the store holds fewer objects than a count.
std::vector<int> DistractorCounts(const EvalOptions& o) {
  if (o.distractors_from.empty()) {
    return o.distractors.empty() ? std::vector<int>{0} : o.distractors;
  }
  const std::size_t held = ObjectsHeld(o.distractors_from);
  if (o.distractors.empty() && held > static_cast<std::size_t>(kMaxDistractors)) {
    throw std::invalid_argument("--distractors-from " + o.distractors_from + " holds " +
                                std::to_string(held) + " objects, more than " +
                                std::to_string(kMaxDistractors) + ": choose --distractors N");
  }
  if (o.distractors.empty()) return {static_cast<int>(held)};
  for (const int count : o.distractors) {
    if (static_cast<std::size_t>(count) > held) {
      throw std::invalid_argument("--distractors " + std::to_string(count) + ": " +
                                  o.distractors_from + " holds " + std::to_string(held) +
                                  " objects");
    }
  }
  return o.distractors;
}

// `--distractors-from FILE` into `options`: its first `options.distractors` objects in id order,
// read when the runner asks for them; the source throws std::invalid_argument when an object is
// in another variant than the one evaluated.
void SetDistractorsFrom(const EvalOptions& o, EvaluationOptions& options) {
  if (o.distractors_from.empty()) return;
  options.distractors_from = o.distractors_from;
  options.distractor_models = [file = o.distractors_from](int count, DescriptorVariant variant) {
    std::vector<ObjectModel> models = SqliteModelStore(file).LoadAll();
    models.resize(std::min(models.size(), static_cast<std::size_t>(count)));
    for (const ObjectModel& model : models) {
      if (model.variant != variant) {
        throw std::invalid_argument(
            "--distractors-from " + file + ": object \"" + model.name + "\" is described in " +
            std::string(VariantName(model.variant)) + ", the evaluation in " +
            std::string(VariantName(variant)) + " (choose --variant " +
            std::string(VariantName(model.variant)) + ")");
      }
    }
    return models;
  };
}

// The flags that describe one evaluation's output, refused with several --distractors counts.
void RefuseOnePerRunFlags(const EvalOptions& o) {
  const auto refuse = [](const std::string& flag) {
    throw std::invalid_argument(flag +
                                " does not apply to several --distractors counts: run one count");
  };
  if (!o.queries.empty()) refuse("--queries");
  if (!o.sweeps.empty()) refuse("--sweep");
  if (!o.verdicts.empty()) refuse("--verdicts");
  if (!o.recognition_plot.empty()) refuse("--recognition-plot");
}

// The sweep's table, then the CSV and the plot the options ask for.
void WriteDistractorSweep(const std::vector<EvaluationReport>& reports, const EvalOptions& o) {
  std::cout << DistractorSweepMarkdown(reports) << std::flush;
  if (!o.csv.empty()) {
    std::ofstream csv(o.csv);
    if (csv) WriteDistractorSweepCsv(reports, csv);
    if (!csv) throw std::runtime_error(o.csv + ": cannot write the CSV file");
  }
  if (!o.plot.empty()) WritePng(DrawDistractorSweepPlot(reports), o.plot);
}

int RunEval(const EvalOptions& o) {
  try {
    auto [known, unknown] =
        SelectDataset({o.layout, o.data, o.manifest, o.objects, o.unknown_objects});
    EvaluationOptions options = ToEvaluationOptions(o);
    if (!o.boxes.empty()) {
      const std::map<std::string, ImageBox> boxes = ReadBoxes(o.boxes);
      AttachBoxes(known, boxes, o.box_margin);
      AttachBoxes(unknown, boxes, o.box_margin);
      // Captured frames are described in their boxes as the model views are.
      if (!o.queries.empty()) options.boxes = boxes;
    }
    SetBoxMargin(known, o.box_margin);
    SetBoxMargin(unknown, o.box_margin);
    options.box_margin = o.box_margin;
    SetDistractorsFrom(o, options);
    const std::vector<int> counts = DistractorCounts(o);
    std::unique_ptr<ProgressBar> progress;
    if (!o.no_progress) {
      progress = std::make_unique<ProgressBar>(std::cerr, ::isatty(STDERR_FILENO) == 1);
      options.progress = [&progress](std::string_view stage, std::size_t done, std::size_t total) {
        progress->Update(stage, done, total);
      };
    }
    std::cerr << "orbit eval: seed " << options.seed << ", " << known.size() << " known images"
              << (unknown.empty() ? "" : ", " + std::to_string(unknown.size()) + " unknown images")
              << ", " << (options.threads > 0 ? options.threads : AvailableCpus()) << " threads\n";
    if (!o.queries.empty() && o.active) {
      throw std::invalid_argument(
          "--active does not apply to --queries: captured sequences "
          "have their views already");
    }
    if (!o.queries.empty() && !unknown.empty()) {
      throw std::invalid_argument(
          "--unknown-objects does not apply to --queries: a captured sequence of an object "
          "outside the model set is an unknown query");
    }
    if (counts.size() > 1) {
      RefuseOnePerRunFlags(o);
      std::vector<EvaluationReport> reports;
      for (const int count : counts) {
        options.distractors = count;
        if (progress) {
          const std::string prefix = std::to_string(count) + " distractors: ";
          options.progress = [&progress, prefix](std::string_view stage, std::size_t done,
                                                 std::size_t total) {
            progress->Update(prefix + std::string(stage), done, total);
          };
        }
        reports.push_back(RunEvaluation(known, unknown, options));
        std::cout << MarkdownReport(reports.back()) << std::flush;
      }
      progress.reset();
      WriteDistractorSweep(reports, o);
      return 0;
    }
    options.distractors = counts.front();
    const EvaluationReport report =
        o.queries.empty() ? RunEvaluation(known, unknown, options)
                          : RunCaptureEvaluation(known, ReadQueryCaptures(o.queries), options);
    progress.reset();
    WriteReport(report, o);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "orbit eval: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace

void AddEvalCommand(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<EvalOptions>();
  CLI::App* command = app.add_subcommand(
      "eval",
      "Run the evaluation protocol of docs/design.md on a dataset: per object, n random views\n"
      "are the query (their neighbours within 10 degrees leave the model), unchanged (df),\n"
      "motion-blurred (mb) or noisy (gn), with noisy azimuths; prints the top-1 hit rate per\n"
      "method x distortion x n as Markdown, plus time per query and model memory.\n"
      "Your own captures instead: --queries FILE against the model set of --data/--manifest,\n"
      "or --server HOST:PORT --queries FILE against the objects a running server holds.");
  command
      ->add_option("--layout", o->layout,
                   "coil100: a folder of objN__A.png (--data); manifest: a CSV file "
                   "(--manifest); default: manifest when --manifest is given, else coil100")
      ->check(CLI::IsMember({"coil100", "manifest"}));
  command->add_option("--data", o->data, "the COIL-100 folder (--layout coil100)");
  command->add_option("--manifest", o->manifest,
                      "CSV with columns path,object,azimuth[,elevation][,x,y,w,h: the object's "
                      "box] (--layout manifest, implied); " +
                          std::string(kRelativePathsHelp));
  command
      ->add_option(
          "--methods", o->methods,
          "comma-separated: product (what `orbit serve` runs by default: " + DescribeProduct() +
              "; evaluated on its own variant, added when --variant lacks it, and on every "
              "variant of --variant with appearance channels, as `orbit serve --variant` runs "
              "it) and "
              "every engine a server runs (the thesis' seven and vci-hmm, the two "
              "together)")
      ->delimiter(',')
      ->check(CLI::IsMember(DefaultMethods()))
      ->capture_default_str();
  command
      ->add_option(
          "--variant", o->variants,
          "descriptor variant(s) of the thesis' engines: cedd-lire, cedd-full, cedd-robust, "
          "cedd-hsv-hog, cedd-hsv-layout, cedd-soft-hsv-hog")
      ->delimiter(',')
      ->check(CLI::IsMember(VariantNames()))
      ->capture_default_str();
  CLI::Option* distortions =
      command
          ->add_option("--distortions", o->distortions,
                       "query distortions, comma-separated: df, mb, gn (the protocol's) or "
                       "mb:len=L:angle=A, gn:var=V, jpeg:q=Q, gain:G, lowres:S, joined by + to "
                       "combine, e.g. mb:len=9:angle=70+gn:var=0.004")
          ->delimiter(',')
          ->check(CLI::Validator(
              [](std::string& text) {
                try {
                  ParseDistortionSpec(text);
                } catch (const std::invalid_argument& e) {
                  return std::string(e.what());
                }
                return std::string();
              },
              "SPEC"))
          ->capture_default_str();
  command
      ->add_option("--sweep", o->sweeps,
                   "distortion strengths to sweep, comma-separated: mb (blur length 5..25 px at "
                   "changing angles), gn (variance 0.002..0.03), jpeg (quality 10..60), gain "
                   "(0.6..1.4), or AXIS:FROM..TO; adds hit rate against strength to the report, "
                   "--csv and --plot then hold the sweep (without --distortions, only the sweep "
                   "is run)")
      ->delimiter(',')
      ->check([o](const std::string& text) {
        try {
          ParseSweep(text, o->sweep_steps);
          return std::string();
        } catch (const std::invalid_argument& e) {
          return std::string(e.what());
        }
      });
  command->add_option("--sweep-steps", o->sweep_steps, "strengths per sweep, ends included")
      ->check(CLI::Range(kMinSweepSteps, kMaxSweepSteps))
      ->capture_default_str();
  command->add_option("--n", o->ns, "query lengths (frames per query)")
      ->delimiter(',')
      ->check(CLI::Range(1, kMaxWindow))
      ->capture_default_str();
  command->add_option("--trials", o->trials, "trials per object and n")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->add_option("--seed", o->seed, "seed of every random draw")->capture_default_str();
  command
      ->add_option("--orientation", o->orientation,
                   "use: query frames carry the device's azimuth; ignore: they carry none, as "
                   "from a device without an orientation sensor (the same methods on the "
                   "descriptors alone)")
      ->check(CLI::IsMember({"use", "ignore"}))
      ->capture_default_str();
  command
      ->add_option("--quality-reading", o->quality_reading,
                   "use: query frames carry their measured noise and blur (Frame.quality), as "
                   "from the client library, and the calibrated rule allows noisy and blurred "
                   "windows more (core/decision/quality_allowance.h); ignore: they carry none")
      ->check(CLI::IsMember({"use", "ignore"}))
      ->capture_default_str();
  command->add_option("--boxes", o->boxes,
                      "CSV with columns path,x,y,w,h (a dataset's boxes.csv): describe each "
                      "image's box, grown by --box-margin, instead of the whole image (with "
                      "--queries: each query frame's too, a row for every frame); " +
                          std::string(kRelativePathsHelp));
  AddBoxMarginOption(*command, o->box_margin);
  command->add_option("--objects", o->objects,
                      "objects in the model set, e.g. 1-20 or 1-5,9 (coil100: object numbers; "
                      "manifest: order of first appearance); default all");
  command->add_option("--unknown-objects", o->unknown_objects,
                      "objects left out of the model set and queried as unknown (recognition: "
                      "reports accept / reject rates), e.g. 91-100");
  command->add_option("--index", o->index, "exact: brute force; kdtree: FLANN + exact re-ranking")
      ->check(CLI::IsMember({"exact", "kdtree"}))
      ->capture_default_str();
  command->add_option("--kd-trees", o->kd_trees, "FLANN randomised kd-trees")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->add_option("--kd-checks", o->kd_checks, "leaves FLANN visits per query")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->add_option("--kd-candidates", o->kd_candidates, "views FLANN proposes for re-ranking")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->add_option("--threshold", o->threshold, "Th of the accept / unknown rule")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command
      ->add_option("--rejection", o->rejection,
                   "accept / unknown rule of the thesis' engines: th (their own rule in "
                   "docs/design.md, --threshold) "
                   "or calibrated (the product's, --false-accept-rate); the product always "
                   "uses its own")
      ->check(CLI::IsMember({"th", "calibrated"}))
      ->capture_default_str();
  std::ostringstream engines_rate;
  engines_rate << EngineOptions{}.false_accept_rate;
  command
      ->add_option("--false-accept-rate", o->false_accept_rate,
                   "the calibrated rule's target share of unknown objects accepted, in (0, 1) "
                   "(default: " +
                       engines_rate.str() +
                       " for the engines; for the product, on each variant the variant's, as "
                       "`orbit serve` takes it: " +
                       DescribeProductFalseAcceptRates() + ")")
      ->check(CLI::Range(1e-6, 1 - 1e-6));
  command
      ->add_option("--known-accept-rate", o->known_accept_rate,
                   "the share of the known objects' own windows the calibrated rule raises its "
                   "threshold to accept where look-alikes need more, in [0, 1); 0: the target "
                   "rate alone")
      ->check(CLI::Range(0.0, 1 - 1e-6))
      ->capture_default_str();
  command->add_option("--verdicts", o->verdicts,
                      "also write every query's answer as CSV (its object, the top-1 object: which "
                      "look-alikes are taken for which; decision, unknown statistic, p-value, "
                      "confidence, pose error)");
  command->add_flag("--active", o->active,
                    "active vision: after its first two views, each query takes its next view "
                    "--active-step degrees on in the direction its method's latest update "
                    "suggested, instead of at random");
  command
      ->add_option("--active-policy", o->active_policy,
                   "with --active, which way each step goes: follow (the method's suggestion), "
                   "one-way (always the same way: the control that measures the suggestion), "
                   "oracle (both ways at every step, keeping the path best for the truth: the "
                   "bound of any left / right suggestion; 2^(n-2) paths per query)")
      ->check(CLI::IsMember({"follow", "one-way", "oracle"}))
      ->capture_default_str();
  command->add_option("--active-step", o->active_step, "degrees per step of --active")
      ->check(CLI::Range(1.0, 180.0))
      ->capture_default_str();
  command->add_option("--recognition-plot", o->recognition_plot,
                      "with --unknown-objects: also draw known queries right and accepted "
                      "against unknown queries accepted as the target false-accept rate sweeps "
                      "0.001..1 (PNG)");
  command
      ->add_option("--orientation-weight", o->orientation_weight,
                   "w of vci's orientation term, per radian")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  command->add_option("--list-length", o->list_length, "N_L: views per VCI retrieval list")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->add_option("--hmm-states", o->hmm_states, "HMM states (azimuth sectors) per object")
      ->check(CLI::Range(1, kMaxHmmStates))
      ->capture_default_str();
  command
      ->add_option("--hmm-sharpness", o->hmm_sharpness,
                   "hmm decodes with emissions to the power 2^S (0: the thesis' HMM)")
      ->check(CLI::Range(0, kMaxHmmSharpness))
      ->capture_default_str();
  command
      ->add_option("--nearest-view-weight", o->nearest_view_weight,
                   "share of each ranked object's score the thesis' engines take from the "
                   "window's nearest views (1 - T_EIS) instead of their own (0: the thesis' "
                   "engines; the product's is its own)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  command
      ->add_option("--candidates", o->candidates,
                   "the HMM (and the product) scores only this many objects per frame, proposed "
                   "by the index from their sector summaries, once the model set holds more than "
                   "--candidates-above objects (0: the method's own setting; the product's is " +
                       std::to_string(kProductCandidateObjects) + " above " +
                       std::to_string(kProductCandidatesAbove) + ")")
      ->check(CLI::Range(0, kMaxCandidateObjects))
      ->capture_default_str();
  command
      ->add_option("--distractors", o->distractors,
                   "add this many generated objects (random textured boxes and cylinders, " +
                       std::to_string(kDistractorViews) +
                       " views each) to every model set, never queried: recognition among many "
                       "other objects. Several counts, e.g. 0,1000,9900, run the evaluation once "
                       "per count and report hit rate and unknowns rejected against the count "
                       "(--csv, --plot)")
      ->delimiter(',')
      ->check(CLI::Range(0, kMaxDistractors));
  command
      ->add_option(
          "--distractors-from", o->distractors_from,
          "take the distractors from this model store (a SQLite file, read; the evaluation "
          "writes no object to it) "
          "instead of generating them: its first --distractors objects in id order, "
          "or all of them; they must be described in the evaluated variant. "
          "`orbit import --layout distractors --objects 1-N` with the same --seed "
          "stores the objects --distractors N generates; any other catalogue works too")
      ->check(CLI::ExistingFile);
  command
      ->add_option("--candidates-above", o->candidates_above,
                   "with --candidates: the model-set size above which candidates are used")
      ->check(CLI::Range(0, kMaxCandidatesAbove))
      ->capture_default_str();
  command->add_option("--csv", o->csv,
                      "also write method,variant,distortion,n,trials,hits,hit_rate,ms_per_query");
  command->add_option("--plot", o->plot, "also draw hit rate against n as a PNG file");
  command->add_option("--threads", o->threads, "worker threads (default: every available core)")
      ->check(CLI::NonNegativeNumber);
  command->add_flag("--no-progress", o->no_progress, "no progress bar on stderr");
  command
      ->add_option("--queries", o->queries,
                   "CSV of your own query captures, columns path,object,sequence[,azimuth]: "
                   "each sequence is one query, recognised with its first n frames against "
                   "the model set of --data/--manifest (all of its images), or by --server; an "
                   "object not in the model set is an unknown query; --distortions defaults to "
                   "df (as captured); " +
                       std::string(kRelativePathsHelp))
      ->check(CLI::ExistingFile);
  AddNetworkOptions(*command, o->network, /*server_required=*/false)
      ->description(
          "a running Orbit server, HOST:PORT: with --queries, stream each captured sequence to "
          "it as one recognition session, with its own objects, defaults and your --token, and "
          "report its answers as the local --queries mode does (the flags of a local model set "
          "do not apply)");
  command->callback([o, distortions, command, &exit_code] {
    if (!o->queries.empty() && distortions->count() == 0) o->distortions = {"df"};
    if (!o->sweeps.empty() && distortions->count() == 0) o->distortions.clear();
    if (!o->network.server.empty()) {
      try {
        RefuseLocalFlags(*command, *o);
      } catch (const std::invalid_argument& e) {
        std::cerr << "orbit eval: " << e.what() << "\n";
        exit_code = 1;
        return;
      }
      exit_code = RunServerEval(*o);
      return;
    }
    exit_code = RunEval(*o);
  });
}

}  // namespace orbit::cli
