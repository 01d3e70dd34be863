// Smoke tests of `orbit eval` on a few COIL-100 objects: the table, the CSV and the plot a user
// gets, and the errors for bad options. Small on purpose (seconds); the full protocol is a
// command (docs/results/coil100-reproduction.md).
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "tests/support/client_test_support.h"
#include "tests/support/free_port.h"
#include "tests/support/server_process.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

struct CsvRow {
  std::map<std::string, std::string> field;
  double number(const std::string& name) const { return std::stod(field.at(name)); }
};

// The fields of a CSV line, an empty last field included.
std::vector<std::string> SplitComma(const std::string& line) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  for (std::size_t comma; (comma = line.find(',', start)) != std::string::npos; start = comma + 1) {
    fields.push_back(line.substr(start, comma - start));
  }
  fields.push_back(line.substr(start));
  return fields;
}

// Reads a CSV with a header; returns the header and the rows.
std::pair<std::string, std::vector<CsvRow>> ReadCsv(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string header, line;
  std::getline(in, header);
  const std::vector<std::string> names = SplitComma(header);
  std::vector<CsvRow> rows;
  while (std::getline(in, line)) {
    const std::vector<std::string> values = SplitComma(line);
    EXPECT_EQ(values.size(), names.size()) << line;
    CsvRow row;
    for (std::size_t i = 0; i < names.size() && i < values.size(); ++i)
      row.field[names[i]] = values[i];
    rows.push_back(row);
  }
  return {header, rows};
}

class EvalCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("orbit_eval_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
    coil_ = (testing::DataDir() / "coil-100").string();
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // `orbit eval` on COIL-100's objects 1-3, one trial, n = 2, without a progress bar, and `args`.
  testing::CommandResult EvalThreeObjects(const std::string& args) const {
    return testing::RunCommand(testing::OrbitBinary() + " eval --data " + coil_ +
                               " --objects 1-3 --n 2 --trials 1 --no-progress " + args);
  }

  std::filesystem::path dir_;
  std::string coil_;
};

TEST_F(EvalCommandTest, PrintsTableCsvAndPlotForTheChosenMethods) {
  const auto csv = dir_ / "result.csv", plot = dir_ / "result.png";
  const testing::CommandResult result = testing::RunCommand(
      testing::OrbitBinary() + " eval --layout coil100 --data " + coil_ +
      " --objects 1-4 --unknown-objects 5 --methods eis,vci,hmm --distortions df,mb --n 1,2"
      " --trials 2 --seed 7 --index exact --threads 2 --csv " +
      csv.string() + " --plot " + plot.string());
  ASSERT_EQ(result.exit_code, 0) << result.err;

  // The Markdown table: one row per distortion x method, one column per n.
  EXPECT_THAT(result.out, HasSubstr("| distortion | method | n=1 | n=2 | ms/query (n=2) |"));
  EXPECT_THAT(result.out, HasSubstr("| DF | eis |"));
  EXPECT_THAT(result.out, HasSubstr("| MB | hmm |"));
  EXPECT_THAT(result.out, HasSubstr("Seed 7"));
  EXPECT_THAT(result.out, HasSubstr("4 known objects, 1 unknown object,"));
  EXPECT_THAT(result.out, HasSubstr("Model memory (cedd-lire): 4 objects, 288 views"));
  EXPECT_THAT(result.out, HasSubstr("recognition (%)"));
  EXPECT_THAT(result.out, Not(HasSubstr("siis")));  // not asked for
  EXPECT_THAT(result.out, Not(HasSubstr("| GN |")));

  const auto [header, rows] = ReadCsv(csv);
  EXPECT_EQ(header,
            "method,variant,distortion,n,trials,hits,hit_rate,ms_per_query,"
            "accepted,accept_rate,unknown_trials,rejected,reject_rate");
  ASSERT_EQ(rows.size(), 3u * 2 * 2);  // methods x distortions x n
  for (const CsvRow& row : rows) {
    EXPECT_THAT((std::vector<std::string>{"eis", "vci", "hmm"}),
                ::testing::Contains(row.field.at("method")));
    EXPECT_EQ(row.field.at("variant"), "cedd-lire");
    EXPECT_EQ(row.number("trials"), 8);          // 4 objects x 2 trials
    EXPECT_EQ(row.number("unknown_trials"), 2);  // 1 object x 2 trials
    EXPECT_LE(row.number("hits"), 8);
    EXPECT_NEAR(row.number("hit_rate"), row.number("hits") / 8, 1e-4);
    EXPECT_LE(row.number("accepted"), row.number("hits"));
    EXPECT_GT(row.number("ms_per_query"), 0);
    // Four very different objects, unchanged views 5 degrees from the removed ones' neighbours:
    // every method finds nearly all of them.
    if (row.field.at("distortion") == "df") {
      EXPECT_GE(row.number("hit_rate"), 0.75)
          << row.field.at("method") << " n=" << row.field.at("n");
    }
  }

  const cv::Mat image = cv::imread(plot.string());
  ASSERT_FALSE(image.empty());
  EXPECT_EQ(image.cols, 2 * 460);  // one panel per distortion
  EXPECT_GT(image.rows, 340);
  cv::Mat grey;
  cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  EXPECT_GT(cv::countNonZero(grey < 128), 1000);  // axes, text and lines were drawn
}

TEST_F(EvalCommandTest, CountsDoNotDependOnThreadsOrLayout) {
  // The same objects as a manifest (object order and image order as in the folder) and as a
  // COIL-100 folder, with 1 and 2 threads: the same trials and the same noise, so the same hits.
  std::ofstream manifest(dir_ / "set.csv");
  manifest << "path,object,azimuth\n";
  for (int object : {1, 2, 3, 4, 5, 6}) {
    for (int azimuth = 0; azimuth < 360; azimuth += 5) {
      manifest << coil_ << "/obj" << object << "__" << azimuth << ".png,obj" << object << ","
               << azimuth << "\n";
    }
  }
  manifest.close();
  const std::string common =
      " --methods eis,vci-bm,hmm --distortions gn --n 1,2 --trials 3 --seed 3 --no-progress --csv ";
  const auto coil =
      testing::RunCommand(testing::OrbitBinary() + " eval --layout coil100 --data " + coil_ +
                          " --objects 1-6 --threads 2" + common + (dir_ / "a.csv").string());
  ASSERT_EQ(coil.exit_code, 0) << coil.err;
  const auto listed = testing::RunCommand(
      testing::OrbitBinary() + " eval --layout manifest --manifest " + (dir_ / "set.csv").string() +
      " --threads 1" + common + (dir_ / "b.csv").string());
  ASSERT_EQ(listed.exit_code, 0) << listed.err;
  const auto a = ReadCsv(dir_ / "a.csv").second, b = ReadCsv(dir_ / "b.csv").second;
  ASSERT_EQ(a.size(), 6u);
  ASSERT_EQ(b.size(), 6u);
  // GN queries are hit about half the time: six equal counts of 18 by chance are unlikely.
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].field.at("method"), b[i].field.at("method"));
    EXPECT_EQ(a[i].field.at("trials"), "18");
    EXPECT_EQ(a[i].field.at("hits"), b[i].field.at("hits")) << a[i].field.at("method");
  }
}

TEST_F(EvalCommandTest, ExplainsBadOptions) {
  const std::string eval = testing::OrbitBinary() + " eval ";
  auto r = testing::RunCommand(eval + "--layout manifest --objects 1-2");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("--layout manifest needs --manifest FILE"));
  r = testing::RunCommand(eval + "--data " + coil_ + " --methods eis,magic");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.err, HasSubstr("magic"));
  r = testing::RunCommand(eval + "--data " + coil_ + " --objects 1-3 --unknown-objects 3");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("object 3 is in both --objects and --unknown-objects"));
  r = testing::RunCommand(eval + "--data " + coil_ + " --objects 101");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("no image of object 101"));
  r = testing::RunCommand(eval + "--data " + coil_ + " --n 0");
  EXPECT_NE(r.exit_code, 0);
  r = testing::RunCommand(eval + "--layout coil100 --manifest " + (dir_ / "m.csv").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("--layout coil100 needs --data DIR; a --manifest FILE goes with "
                               "--layout manifest"));
  r = testing::RunCommand(eval + "--data " + coil_ + " --manifest " + (dir_ / "m.csv").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("give --data DIR (a COIL-100 folder) or --manifest FILE (a CSV "
                               "file), not both"));
  r = testing::RunCommand(eval + "--data " + coil_ + " --distortions df,mb:len=0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("distortion 'mb:len=0': len must be in [1, 100]"));
}

// --distractors-from: a store's objects join every model set as distractors. The objects
// `orbit import --layout distractors` stored give the counts that generating them gives; a store
// holding a twin of a queried object (COIL-100's object 1 imported whole, so with the views the
// protocol takes out of the object's own model around each query) takes that object's hits, as
// a sweep over the count shows; a store too small, or in another variant, is refused by name.
TEST_F(EvalCommandTest, DistractorsFromAStoreJoinTheModelSet) {
  const std::string orbit = testing::OrbitBinary();
  const std::string catalogue = (dir_ / "catalogue.db").string();
  const std::string twin = (dir_ / "twin.db").string();
  const std::string other_variant = (dir_ / "robust.db").string();
  for (const std::string& import :
       {" --db " + catalogue + " --layout distractors --objects 1-2",
        " --db " + twin + " --layout coil100 --data " + coil_ + " --objects 1",
        " --db " + other_variant + " --layout coil100 --data " + coil_ +
            " --objects 2 --variant cedd-robust"}) {
    const auto imported = testing::RunCommand(orbit + " import --threads 2" + import);
    ASSERT_EQ(imported.exit_code, 0) << import << ": " << imported.err;
  }
  const std::string eval = orbit + " eval --data " + coil_ +
                           " --objects 1-3 --methods product --variant cedd-soft-hsv-hog --n 1 "
                           "--trials 3 --no-progress --csv ";
  const auto hits = [this](const std::string& csv) {
    std::vector<std::string> counts;
    for (const CsvRow& row : ReadCsv(dir_ / csv).second) counts.push_back(row.field.at("hits"));
    return counts;
  };

  const auto generated = testing::RunCommand(eval + (dir_ / "generated.csv").string() +
                                             " --distortions gn,mb --distractors 2");
  ASSERT_EQ(generated.exit_code, 0) << generated.err;
  EXPECT_THAT(generated.out, HasSubstr("2 distractor objects generated in the model set"));
  const auto stored = testing::RunCommand(eval + (dir_ / "stored.csv").string() +
                                          " --distortions gn,mb --distractors-from " + catalogue);
  ASSERT_EQ(stored.exit_code, 0) << stored.err;
  EXPECT_THAT(stored.out,
              HasSubstr("2 distractor objects from " + catalogue + " in the model set"));
  EXPECT_EQ(hits("stored.csv"), hits("generated.csv"));
  EXPECT_EQ(hits("stored.csv").size(), 2u);

  // A sweep of the twin store's first 0 and 1 objects: without it every DF query of objects 1-3
  // is hit (9 of 9), with it object 1's three are lost.
  const auto sweep = testing::RunCommand(eval + (dir_ / "sweep.csv").string() +
                                         " --distortions df --distractors 0,1 --distractors-from " +
                                         twin + " --plot " + (dir_ / "sweep.png").string());
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  EXPECT_THAT(sweep.out, HasSubstr("| df | product | 1 | 100.0 | 66.7 |"));
  std::vector<std::string> rows;
  for (const CsvRow& row : ReadCsv(dir_ / "sweep.csv").second) {
    rows.push_back(row.field.at("distractors") + " " + row.field.at("trials") + " " +
                   row.field.at("hits"));
  }
  EXPECT_EQ(rows, (std::vector<std::string>{"0 9 9", "1 9 6"}));
  EXPECT_FALSE(cv::imread((dir_ / "sweep.png").string()).empty());
  const auto one_per_run = testing::RunCommand(eval + (dir_ / "x.csv").string() +
                                               " --distractors 0,1 --distractors-from " + twin +
                                               " --verdicts " + (dir_ / "v.csv").string());
  EXPECT_EQ(one_per_run.exit_code, 1);
  EXPECT_THAT(
      one_per_run.err,
      HasSubstr("--verdicts does not apply to several --distractors counts: run one count"));

  const auto too_many = testing::RunCommand(eval + (dir_ / "x.csv").string() +
                                            " --distractors 3 --distractors-from " + catalogue);
  EXPECT_EQ(too_many.exit_code, 1);
  EXPECT_THAT(too_many.err, HasSubstr("--distractors 3: " + catalogue + " holds 2 objects"));
  const auto variant = testing::RunCommand(eval + (dir_ / "x.csv").string() +
                                           " --distractors-from " + other_variant);
  EXPECT_EQ(variant.exit_code, 1);
  EXPECT_THAT(variant.err,
              HasSubstr("--distractors-from " + other_variant +
                        ": object \"obj2\" is described in cedd-robust, the evaluation in "
                        "cedd-soft-hsv-hog (choose --variant cedd-robust)"));
}

// The lines of `text` that start with `prefix`.
std::vector<std::string> LinesStartingWith(const std::string& text, const std::string& prefix) {
  std::vector<std::string> lines;
  std::stringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(prefix, 0) == 0) lines.push_back(line);
  }
  return lines;
}

// A user's own captures (--queries) against a manifest's model set: objects 1-3 of COIL-100
// every 10 degrees; the queries are views in between, copied beside the queries file and named
// relative to it: a sequence of four frames of object 1 with the device's azimuths, and two
// frames of object 9, which is not in the model set. Only the product runs.
class CapturedQueriesTest : public EvalCommandTest {
 protected:
  void SetUp() override {
    EvalCommandTest::SetUp();
    std::ofstream manifest(dir_ / "set.csv");
    manifest << "path,object,azimuth\n";
    for (int object : {1, 2, 3}) {
      for (int azimuth = 0; azimuth < 360; azimuth += 10) {
        manifest << coil_ << "/obj" << object << "__" << azimuth << ".png,obj" << object << ","
                 << azimuth << "\n";
      }
    }
    std::filesystem::create_directories(dir_ / "walks" / "frames");
    queries_ = dir_ / "walks" / "queries.csv";
    std::ofstream queries(queries_);
    queries << "path,object,sequence,azimuth\n";
    for (const auto& [object, azimuth, sequence] : std::vector<std::tuple<int, int, std::string>>{
             {1, 5, "a"}, {1, 15, "a"}, {1, 25, "a"}, {1, 35, "a"}, {9, 5, "c"}, {9, 15, "c"}}) {
      const std::string name = "obj" + std::to_string(object) + "__" + std::to_string(azimuth);
      std::filesystem::copy_file(coil_ + "/" + name + ".png",
                                 dir_ / "walks" / "frames" / (name + ".png"));
      queries << "frames/" << name << ".png,obj" << object << "," << sequence << "," << azimuth + 40
              << "\n";
    }
  }

  // `orbit eval` of these captures with --manifest alone (the layout implied) and `extra`.
  testing::CommandResult Eval(const std::string& extra) const {
    return testing::RunCommand(testing::OrbitBinary() + " eval --manifest " +
                               (dir_ / "set.csv").string() + " --queries " + queries_.string() +
                               " --methods product --no-progress" + extra);
  }

  std::filesystem::path queries_;
};

TEST_F(CapturedQueriesTest, AnNLongerThanEverySequenceReadsAsNothingCounted) {
  const testing::CommandResult r = Eval(" --n 1,4,6");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("| distortion | method | n=1 | n=4 | n=6 | ms/query (n=6) |"));
  // The hit-rate table, then the recognition table: at n=6 no sequence was asked, so neither
  // a rate nor a time is printed.
  const std::vector<std::string> rows = LinesStartingWith(r.out, "| DF | product |");
  ASSERT_EQ(rows.size(), 2u) << r.out;
  EXPECT_THAT(rows[0], ::testing::EndsWith(" | - | - |"));
  EXPECT_THAT(rows[0], Not(HasSubstr("| - | - | - |")));  // n=1 and n=4 were counted
  EXPECT_THAT(rows[1], ::testing::EndsWith(" | - / - |"));
  EXPECT_THAT(rows[1], HasSubstr("| 100.0 / 100.0 |"));  // n=1: object 1 found, object 9 rejected
  EXPECT_THAT(r.out,
              HasSubstr("| product | cedd-soft-hsv-hog | DF | 6 | - | - | - | - | - | - | - |"));
}

TEST_F(CapturedQueriesTest, TheReportNamesOnlyWhatRanAndSaysWhyPoseIsNotMeasured) {
  const testing::CommandResult r = Eval(" --n 2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("Model memory (cedd-soft-hsv-hog): 3 objects, 108 views"));
  // The default --variant cedd-lire is listed but no method ran on it; the thesis' engine
  // options (window, N_L, Th, ...) are not the product's.
  EXPECT_THAT(r.out, Not(HasSubstr("cedd-lire")));
  EXPECT_THAT(r.out, Not(HasSubstr("Engines:")));
  EXPECT_THAT(r.out, Not(HasSubstr("Th ")));
  EXPECT_THAT(r.out, HasSubstr("product: what `orbit serve` runs by default"));
  // The queries carry azimuths, but a device's azimuths do not say which side of the model a
  // frame shows: the pose columns stay empty, and the report says why.
  EXPECT_THAT(r.out, HasSubstr("| pose median | pose p90 |"));
  EXPECT_THAT(r.out, HasSubstr("Pose error: not measured for captured queries (`--queries`): "
                               "their azimuths are the device's readings"));
}

TEST_F(CapturedQueriesTest, AMissingFrameIsNamedWithTheLineOfTheQueriesFile) {
  std::filesystem::remove(dir_ / "walks" / "frames" / "obj1__15.png");
  const testing::CommandResult r = Eval(" --n 1");
  EXPECT_EQ(r.exit_code, 1);
  // Line 3 of the file: the header, then obj1__5, then obj1__15.
  EXPECT_THAT(r.err, HasSubstr("orbit eval: " + queries_.string() +
                               ":3: " + (dir_ / "walks" / "frames" / "obj1__15.png").string() +
                               ": no such file"));
}

// With --boxes, the captured frames are described in their boxes as the model views are, so each
// frame needs a row as each model image does: boxes for the model set alone name the first
// frame without one instead of describing the frames whole.
TEST_F(CapturedQueriesTest, WithBoxesEveryFrameNeedsOneAsTheModelViewsDo) {
  const std::filesystem::path boxes = dir_ / "boxes.csv";
  {
    std::ofstream file(boxes);
    file << "path,x,y,w,h\n";
    for (int object : {1, 2, 3}) {
      for (int azimuth = 0; azimuth < 360; azimuth += 10) {
        file << coil_ << "/obj" << object << "__" << azimuth << ".png,16,16,96,96\n";
      }
    }
  }
  const testing::CommandResult models_only = Eval(" --n 1 --boxes " + boxes.string());
  EXPECT_EQ(models_only.exit_code, 1);
  EXPECT_THAT(models_only.err,
              HasSubstr("no box for " + (dir_ / "walks" / "frames" / "obj1__5.png").string()));

  {
    std::ofstream file(boxes, std::ios::app);
    for (const std::string name :
         {"obj1__5", "obj1__15", "obj1__25", "obj1__35", "obj9__5", "obj9__15"}) {
      file << (dir_ / "walks" / "frames" / (name + ".png")).string() << ",16,16,96,96\n";
    }
  }
  const testing::CommandResult every_frame = Eval(" --n 1 --boxes " + boxes.string());
  ASSERT_EQ(every_frame.exit_code, 0) << every_frame.err;
  EXPECT_THAT(every_frame.out, HasSubstr("| DF | product | 100.0 |"));
}

TEST_F(EvalCommandTest, HelpSaysWhereTheCsvFilesPathsAreReadFrom) {
  const testing::CommandResult r = testing::RunCommand(testing::OrbitBinary() + " eval --help");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // --manifest, --boxes and --queries.
  const std::string said =
      "a relative path in it is read from the CSV file's own folder, not the working directory";
  int times = 0;
  for (std::size_t at = r.out.find(said); at != std::string::npos; at = r.out.find(said, at + 1))
    ++times;
  EXPECT_EQ(times, 3) << r.out;
  EXPECT_THAT(r.out, HasSubstr("default: manifest when --manifest is given, else coil100"));
}

// Parameterised distortions reach the report under their canonical names, next to the
// protocol's, which keep theirs (in capitals).
TEST_F(EvalCommandTest, ParameterisedDistortionsAreReportedUnderTheirNames) {
  const auto r = EvalThreeObjects("--methods hmm --distortions gn,gn:var=0.004+jpeg:q=30");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("| GN | hmm |"));
  EXPECT_THAT(r.out, HasSubstr("| gn:var=0.004+jpeg:q=30 | hmm |"));
}

// `--methods product --variant cedd-hsv-layout`: the product on a layout store, as `orbit serve
// --variant cedd-hsv-layout` runs it, in the layout's table beside its own variant's, and the
// report says what the row under the other variant is.
TEST_F(EvalCommandTest, ProductOnAnotherVariantIsReportedUnderThatVariant) {
  const auto r = EvalThreeObjects("--methods product --variant cedd-hsv-layout --distortions df");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("### cedd-hsv-layout: hit rate"));
  EXPECT_THAT(r.out, HasSubstr("### cedd-soft-hsv-hog: hit rate"));
  EXPECT_EQ(LinesStartingWith(r.out, "| DF | product |").size(), 2u) << r.out;
  EXPECT_THAT(r.out, HasSubstr("; under another variant, the same pipeline on a store made in "
                               "that variant (`orbit serve --variant`), at that variant's "
                               "target false-accept rate unless the run gives one (0.15, 0.09 "
                               "on cedd-hsv-layout)."));
  // Not said where the product ran on its own variant alone.
  const auto own = EvalThreeObjects("--methods product --distortions df");
  ASSERT_EQ(own.exit_code, 0) << own.err;
  EXPECT_THAT(own.out, HasSubstr("product: what `orbit serve` runs by default"));
  EXPECT_THAT(own.out, Not(HasSubstr("under another variant")));
}

// --sweep: only the swept distortions run (no --distortions given), the report gains the sweep's
// table, --csv holds the sweep and --plot draws hit rate against strength.
TEST_F(EvalCommandTest, SweepReportsHitRateAgainstStrength) {
  const auto csv = dir_ / "sweep.csv", plot = dir_ / "sweep.png";
  const auto r = testing::RunCommand(
      testing::OrbitBinary() + " eval --data " + coil_ +
      " --objects 1-3 --n 1 --trials 1 --methods product --no-progress --sweep jpeg:20..60"
      " --sweep-steps 3 --csv " +
      csv.string() + " --plot " + plot.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("### Sweep: JPEG quality (hit rate %, top-1)"));
  EXPECT_THAT(r.out, HasSubstr("| method | n | 20 | 40 | 60 | worst |"));
  EXPECT_THAT(r.out, HasSubstr("| product (cedd-soft-hsv-hog) | 1 |"));
  EXPECT_THAT(r.out, Not(HasSubstr("| DF |")));
  const auto [header, rows] = ReadCsv(csv);
  EXPECT_EQ(header, "axis,strength,distortion,method,variant,n,trials,hits,hit_rate");
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[1].field.at("distortion"), "jpeg:q=40");
  EXPECT_FALSE(cv::imread(plot.string()).empty());
  const auto bad =
      testing::RunCommand(testing::OrbitBinary() + " eval --data " + coil_ + " --sweep noise");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_THAT(bad.err, HasSubstr("unknown axis \"noise\" (mb, gn, jpeg, gain)"));
}

// --orientation ignore runs the methods without azimuths: vci then answers as vci-w0 does with
// them (tests/core/engines/recognition_engine_test.cc), so the two rows' hit counts are equal.
TEST_F(EvalCommandTest, OrientationIgnoreRunsTheMethodsWithoutAzimuths) {
  const std::string eval = testing::OrbitBinary() + " eval --data " + coil_ +
                           " --objects 1-6 --n 4 --trials 2 --distortions mb --no-progress --csv ";
  const std::string ignored = (dir_ / "ignored.csv").string(), used = (dir_ / "used.csv").string();
  auto r = testing::RunCommand(eval + ignored + " --methods vci --orientation ignore");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("Orientation ignored"));
  r = testing::RunCommand(eval + used + " --methods vci-w0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The first row's trials and hits (columns 5 and 6: method,variant,distortion,n,trials,hits).
  const auto trials_and_hits = [](const std::string& csv) {
    std::ifstream in(csv);
    std::string header, row;
    std::getline(in, header);
    std::getline(in, row);
    std::vector<std::string> fields;
    std::stringstream cells(row);
    for (std::string field; std::getline(cells, field, ',');) fields.push_back(field);
    return fields.size() > 5 ? fields[4] + " " + fields[5] : row;
  };
  EXPECT_EQ(trials_and_hits(ignored), trials_and_hits(used));
  EXPECT_EQ(trials_and_hits(used).substr(0, 3), "12 ");
  r = testing::RunCommand(eval + used + " --orientation sideways");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.err, HasSubstr("--orientation"));
}

// --server: a user's captures streamed to a running server instead of a local model set. The
// server holds COIL-100 objects 1-3, enrolled with `orbit enroll` every 20 degrees; the queries
// are views 10 degrees from the enrolled ones, copied beside the queries file: three frames of
// object 1 and of object 2, two of object 3 (too short for n = 3), and three of object 9, which
// the server does not hold.
class ServerQueriesTest : public EvalCommandTest {
 protected:
  void SetUp() override {
    EvalCommandTest::SetUp();
    queries_ = dir_ / "walks" / "queries.csv";
    std::filesystem::create_directories(dir_ / "walks" / "frames");
    std::ofstream queries(queries_);
    queries << "path,object,sequence,azimuth\n";
    for (const auto& [object, sequence, azimuths] :
         std::vector<std::tuple<int, std::string, std::vector<int>>>{{1, "a", {10, 30, 50}},
                                                                     {2, "b", {190, 210, 230}},
                                                                     {3, "c", {90, 110}},
                                                                     {9, "u", {10, 30, 50}}}) {
      for (const int azimuth : azimuths) {
        const std::string name = "obj" + std::to_string(object) + "__" + std::to_string(azimuth);
        std::filesystem::copy_file(coil_ + "/" + name + ".png",
                                   dir_ / "walks" / "frames" / (name + ".png"));
        queries << "frames/" << name << ".png,obj" << object << "," << sequence << ","
                << azimuth + 40 << "\n";
      }
    }
  }

  std::filesystem::path queries_;
};

TEST_F(ServerQueriesTest, ReportsTheServersAnswersAsTheLocalModeReportsItsOwn) {
  testing::ServerProcess server;
  std::ofstream manifest(dir_ / "set.csv");
  manifest << "path,object,azimuth\n";
  for (int object = 1; object <= 3; ++object) {
    const auto r =
        testing::RunCommand(testing::OrbitBinary() + " enroll --server " + server.address() +
                            " --name obj" + std::to_string(object) +
                            testing::CoilImageArguments(object, testing::EveryTwentyDegrees()));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const int azimuth : testing::EveryTwentyDegrees()) {
      manifest << testing::CoilFile(object, azimuth) << ",obj" << object << "," << azimuth << "\n";
    }
  }
  manifest.close();

  const auto csv = dir_ / "server.csv", verdicts = dir_ / "verdicts.csv";
  const testing::CommandResult r =
      testing::RunCommand(testing::OrbitBinary() + " eval --server " + server.address() +
                          " --queries " + queries_.string() + " --n 1,3 --no-progress --csv " +
                          csv.string() + " --verdicts " + verdicts.string());
  ASSERT_EQ(r.exit_code, 0) << r.err << server.Log();
  EXPECT_THAT(r.out, HasSubstr("Server " + server.address() + " (orbit "));
  EXPECT_THAT(r.out, HasSubstr("3 enrolled objects, 54 views; 1 unknown object among the queries"));
  EXPECT_THAT(r.out, HasSubstr("Queries: 4 captured sequences, 11 frames (`--queries`), each "
                               "streamed as one session with the server's defaults"));
  // The server runs `orbit serve`'s defaults: the product pipeline, in its variant.
  EXPECT_THAT(r.out, HasSubstr("server (product): the server's session defaults, engine hmm, "
                               "window 8"));
  // Object 3's two-frame sequence counts at n = 1, not at n = 3: 3 known queries, then 2.
  EXPECT_THAT(r.out, HasSubstr("### cedd-soft-hsv-hog: hit rate (%), top-1, 2-3 queries per cell"));
  EXPECT_THAT(r.out, Not(HasSubstr("Model memory")));
  EXPECT_THAT(r.out, Not(HasSubstr("Seed ")));
  // Views 10 degrees from enrolled ones of three very different objects: every known query is
  // right, at n = 1 (3 queries) and at n = 3 (2: object 3's sequence is too short).
  const std::vector<std::string> rows = LinesStartingWith(r.out, "| DF | server (product) |");
  ASSERT_EQ(rows.size(), 2u) << r.out;  // hit rates, then recognition
  EXPECT_THAT(rows[0], ::testing::StartsWith("| DF | server (product) | 100.0 | 100.0 |"));

  const auto [header, cells] = ReadCsv(csv);
  EXPECT_EQ(header,
            "method,variant,distortion,n,trials,hits,hit_rate,ms_per_query,"
            "accepted,accept_rate,unknown_trials,rejected,reject_rate");
  ASSERT_EQ(cells.size(), 2u);
  for (const CsvRow& cell : cells) {
    EXPECT_EQ(cell.field.at("method"), "server (product)");
    EXPECT_EQ(cell.field.at("variant"), "cedd-soft-hsv-hog");
    EXPECT_EQ(cell.field.at("distortion"), "df");
    EXPECT_EQ(cell.number("unknown_trials"), 1);  // object 9's sequence, at each n
    EXPECT_GT(cell.number("ms_per_query"), 0);
  }
  EXPECT_EQ(cells[0].field.at("n"), "1");
  EXPECT_EQ(cells[0].number("trials"), 3);
  EXPECT_EQ(cells[0].number("hits"), 3);
  EXPECT_EQ(cells[1].field.at("n"), "3");
  EXPECT_EQ(cells[1].number("trials"), 2);
  EXPECT_EQ(cells[1].number("hits"), 2);

  // Every query's verdict; the server states no unknown statistic nor p-value. Each names the
  // query's object and the server's first candidate: a known query's own (all were right),
  // and for obj9's one of the three the server holds.
  const auto [verdict_header, verdict_rows] = ReadCsv(verdicts);
  ASSERT_EQ(verdict_rows.size(), 4u + 3u);
  for (const CsvRow& verdict : verdict_rows) {
    EXPECT_EQ(verdict.field.at("unknown_statistic"), "");
    EXPECT_EQ(verdict.field.at("unknown_p_value"), "");
    if (verdict.field.at("known") == "1") {
      EXPECT_THAT(verdict.field.at("object"), ::testing::AnyOf("obj1", "obj2", "obj3"));
      EXPECT_EQ(verdict.field.at("answer"), verdict.field.at("object"));
    } else {
      EXPECT_EQ(verdict.field.at("object"), "obj9");
      EXPECT_THAT(verdict.field.at("answer"), ::testing::AnyOf("obj1", "obj2", "obj3"));
    }
  }

  // The same captures against a local model set of the same images, run by the same pipeline:
  // the same answers.
  const auto local_csv = dir_ / "local.csv";
  const testing::CommandResult local = testing::RunCommand(
      testing::OrbitBinary() + " eval --manifest " + (dir_ / "set.csv").string() + " --queries " +
      queries_.string() + " --methods product --n 1,3 --no-progress --csv " + local_csv.string());
  ASSERT_EQ(local.exit_code, 0) << local.err;
  const auto local_cells = ReadCsv(local_csv).second;
  ASSERT_EQ(local_cells.size(), 2u);
  for (std::size_t i = 0; i < cells.size(); ++i) {
    for (const char* field : {"n", "trials", "hits", "accepted", "unknown_trials", "rejected"}) {
      EXPECT_EQ(cells[i].field.at(field), local_cells[i].field.at(field)) << field;
    }
  }
}

TEST_F(ServerQueriesTest, RefusesWhatDoesNotApplyToAServer) {
  const std::string eval = testing::OrbitBinary() + " eval --server 127.0.0.1:1 ";
  const std::string queries = " --queries " + queries_.string();
  auto r = testing::RunCommand(eval + "--n 1");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("orbit eval: --server needs --queries FILE: the captured query "
                               "sequences to send it"));
  r = testing::RunCommand(eval + queries + " --data " + coil_);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("orbit eval: --data does not apply with --server: the model set "
                               "is the objects the server holds"));
  r = testing::RunCommand(eval + queries + " --methods vci");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("--methods does not apply with --server: the server recognises "
                               "with its own variant, engine and session defaults"));
  r = testing::RunCommand(eval + queries + " --distortions df,mb");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("--distortions does not apply with --server: the server is sent "
                               "the frames as captured (df)"));
  r = testing::RunCommand(eval + queries + " --unknown-objects 9");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("--unknown-objects does not apply with --server"));
  r = testing::RunCommand(eval + queries + " --active");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("--active does not apply with --server"));
  r = testing::RunCommand(eval + queries + " --kd-trees 2");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("--kd-trees does not apply with --server"));

  // --distortions df is what a server is sent: accepted, so the command goes on to the server,
  // which is not there.
  const std::string address = "127.0.0.1:" + std::to_string(testing::FreeLoopbackPort());
  r = testing::RunCommand(testing::OrbitBinary() + " eval --server " + address + queries +
                          " --distortions df --no-progress");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("orbit eval: cannot reach a server at " + address + " ("));
  EXPECT_THAT(r.err, HasSubstr("): is `orbit serve` running at " + address + "?"));

  r = testing::RunCommand(testing::OrbitBinary() + " eval --help");
  ASSERT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.out, HasSubstr("a running Orbit server, HOST:PORT: with --queries, stream each"));
  // The command's own description names both ways of measuring one's own captures.
  EXPECT_THAT(r.out, HasSubstr("or --server HOST:PORT --queries FILE against the objects a "
                               "running server holds."));
}

}  // namespace
}  // namespace orbit
