#include "evaluation/evaluation_runner.h"

#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "client/image_file.h"
#include "core/descriptor/cedd.h"
#include "core/descriptor/distortion.h"
#include "core/descriptor/view_description.h"
#include "core/engines/product_pipeline.h"
#include "evaluation/distractor_objects.h"
#include "tests/support/test_data.h"

namespace orbit {
namespace {

using ::testing::HasSubstr;

DatasetImage Coil100Image() {
  return {(testing::DataDir() / "coil-100" / "obj3__20.png").string(), "obj3", 20, std::nullopt,
          std::nullopt};
}

// The evaluation's model views are what every enrollment path stores for the same image
// (DescribeView), with the options' seed as the base of the seed rule.
TEST(DescribeImageTest, ModelViewIsDescribeViewsWithTheOptionsSeed) {
  const DatasetImage image = Coil100Image();
  const cv::Mat pixels = ReadImageFile(image.path);
  const std::uint64_t seed = 7;
  const std::vector<DescriptorVariant> variants{DescriptorVariant::kCeddLire,
                                                DescriptorVariant::kCeddFull};

  const std::vector<DistortionSpec> distortions{ParseDistortionSpec("df"),
                                                ParseDistortionSpec("mb")};
  const std::vector<DescribedImage> described =
      DescribeImage(image, 0, variants, distortions, seed);

  ASSERT_EQ(described.size(), 2u);
  for (std::size_t v = 0; v < variants.size(); ++v) {
    const ViewDescription expected = DescribeView(pixels, variants[v], seed);
    const ModelView& view = described[v].view;
    EXPECT_EQ(view.descriptor, expected.descriptor) << VariantName(variants[v]);
    EXPECT_EQ(view.typical_distance, expected.typical_distance) << VariantName(variants[v]);
    EXPECT_GT(view.typical_distance, 0.0);
    // The seed reaches DescribeView: the default base draws other noise.
    EXPECT_NE(view.typical_distance, DescribeView(pixels, variants[v]).typical_distance);
    EXPECT_EQ(view.azimuth, 20.0);
    EXPECT_FALSE(view.elevation.has_value());
    // DF is the view itself; MB is DescribeView's motion-blurred copy.
    ASSERT_EQ(described[v].queries.size(), 2u);
    EXPECT_EQ(described[v].queries[0], expected.descriptor);
    EXPECT_EQ(described[v].queries[1], expected.distorted[0]);
  }
  EXPECT_NE(described[0].view.descriptor, described[1].view.descriptor);
}

// With a box, its object's region alone (the box grown by the margin, clipped to the image) is
// described and distorted, as a device crops its tracker's box: the same numbers as the cropped
// image. A box not inside the image is refused, naming it.
TEST(DescribeImageTest, ABoxedImageIsDescribedAsItsRegionAlone) {
  DatasetImage image = Coil100Image();
  image.box = ImageBox{10, 30, 60, 90, "boxes.csv:2"};
  image.box_margin = 0.25;  // 15 and round(22.5) = 23 a side: x -5..85, y 7..143, clipped
  const cv::Mat region = ReadImageFile(image.path)(cv::Rect(0, 7, 85, 121));
  const std::vector<DescribedImage> described =
      DescribeImage(image, 0, {DescriptorVariant::kCeddHsvHog}, {ParseDistortionSpec("mb")}, 7);
  const ViewDescription expected = DescribeView(region, DescriptorVariant::kCeddHsvHog, 7);
  ASSERT_EQ(described.size(), 1u);
  EXPECT_EQ(described[0].view.descriptor, expected.descriptor);
  EXPECT_EQ(described[0].view.typical_distance, expected.typical_distance);
  EXPECT_EQ(described[0].queries.at(0), expected.distorted[0]);
  image.box = ImageBox{100, 100, 40, 10, "boxes.csv:2"};
  EXPECT_EQ(testing::ErrorMessageOf(
                [&] { DescribeImage(image, 0, {DescriptorVariant::kCeddLire}, {}, 7); }),
            "boxes.csv:2: x+w must be at most the image's width 128");
}

// A query's noise is seeded by the image's position, so two places draw different noise; any
// distortion spec is applied as ApplyDistortion applies it.
TEST(DescribeImageTest, NoiseQueryIsSeededByThePosition) {
  const DatasetImage image = Coil100Image();
  const cv::Mat pixels = ReadImageFile(image.path);
  const std::vector<DescriptorVariant> lire{DescriptorVariant::kCeddLire};
  const std::vector<DistortionSpec> distortions{ParseDistortionSpec("gn"),
                                                ParseDistortionSpec("jpeg:q=20+gain:0.6")};

  const DescribedImage first = DescribeImage(image, 0, lire, distortions, 7)[0];
  const DescribedImage fifth = DescribeImage(image, 4, lire, distortions, 7)[0];

  EXPECT_EQ(fifth.queries[0], ExtractCedd(AddGaussianNoise(pixels, 0.012, ImageNoiseSeed(7, 4)),
                                          DescriptorVariant::kCeddLire)
                                  .values);
  EXPECT_EQ(fifth.queries[1],
            ExtractCedd(ApplyDistortion(pixels, distortions[1], ImageNoiseSeed(7, 4)),
                        DescriptorVariant::kCeddLire)
                .values);
  EXPECT_NE(first.queries[0], fifth.queries[0]);
  EXPECT_NE(fifth.queries[0], fifth.view.descriptor);
  EXPECT_NE(fifth.queries[1], fifth.view.descriptor);
  // The model view depends on the image alone.
  EXPECT_EQ(first.view.descriptor, fifth.view.descriptor);
  EXPECT_EQ(first.view.typical_distance, fifth.view.typical_distance);
}

TEST(DescribeImageTest, NamesAFileThatCannotBeRead) {
  const DatasetImage missing{"/nonexistent/obj1__0.png", "obj1", 0, std::nullopt, std::nullopt};
  EXPECT_THAT(testing::ErrorMessageOf<std::runtime_error>(
                  [&] { DescribeImage(missing, 0, {DescriptorVariant::kCeddLire}, {}, 1); }),
              HasSubstr("/nonexistent/obj1__0.png"));
}

// Refusals that come before any image is read (the paths do not exist).
TEST(RunEvaluationTest, RefusesAnObjectBothKnownAndUnknownOrWithTooFewViews) {
  const std::vector<DatasetImage> known{{"/none/a0.png", "a", 0, {}, {}},
                                        {"/none/a1.png", "a", 90, {}, {}},
                                        {"/none/b0.png", "b", 0, {}, {}},
                                        {"/none/b1.png", "b", 90, {}, {}}};
  EvaluationOptions options;
  options.query_lengths = {1, 2};
  const std::vector<DatasetImage> unknown{{"/none/b2.png", "b", 180, {}, {}},
                                          {"/none/b3.png", "b", 270, {}, {}}};
  EXPECT_EQ(testing::ErrorMessageOf([&] { RunEvaluation(known, unknown, options); }),
            "object \"b\" is both known and unknown");
  options.query_lengths = {4};
  EXPECT_EQ(testing::ErrorMessageOf([&] { RunEvaluation(known, {}, options); }),
            "object \"a\" has 2 views; n = 4 needs as many");
}

// `product` is the product pipeline (core/engines/product_pipeline.h): its engine with its options,
// on its own variant, which the evaluation adds when it was not asked for, and on no CEDD-only
// variant (the next test: variants with appearance channels). With the engine's options set to
// the product's it is therefore exactly that engine on that variant, query for query.
TEST(RunEvaluationTest, ProductRunsTheProductsEngineOnItsOwnVariant) {
  EvaluationOptions options;
  options.methods = {std::string(kProductMethod), std::string(Product().engine)};
  options.variants = {DescriptorVariant::kCeddLire};
  options.distortions = {ParseDistortionSpec("df"), ParseDistortionSpec("gn:var=0.01")};
  options.query_lengths = {1, 3};
  options.trials = 2;
  options.engine = Product().options;
  const EvaluationReport report =
      RunEvaluation(ListCoil100(testing::CoilDir(), std::vector<int>{1, 2, 3, 4}), {}, options);

  // lire: the engine only; robust: product and the engine. 2 distortions x 2 n each.
  ASSERT_EQ(report.cells.size(), (1 + 2) * 2 * 2u);
  std::vector<const EvaluationCell*> product, engine_on_robust;
  for (const EvaluationCell& cell : report.cells) {
    if (cell.method == kProductMethod) {
      EXPECT_EQ(cell.variant, Product().variant);
      product.push_back(&cell);
    } else if (cell.variant == Product().variant) {
      engine_on_robust.push_back(&cell);
    }
  }
  ASSERT_EQ(product.size(), 4u);
  ASSERT_EQ(engine_on_robust.size(), 4u);
  for (std::size_t i = 0; i < product.size(); ++i) {
    EXPECT_EQ(product[i]->distortion, engine_on_robust[i]->distortion);
    EXPECT_EQ(product[i]->n, engine_on_robust[i]->n);
    EXPECT_EQ(product[i]->trials, 4 * 2);
    EXPECT_EQ(product[i]->hits, engine_on_robust[i]->hits) << product[i]->distortion;
  }
  ASSERT_EQ(report.memory.size(), 2u);
  EXPECT_EQ(report.memory[1].variant, Product().variant);
}

// A server runs the product on a store made in another variant (`orbit serve --variant`); so does
// the evaluation on every listed variant with appearance channels, never on a CEDD-only one it
// was not asked for, and there too it is the product's engine with the product's options.
TEST(RunEvaluationTest, ProductAlsoRunsOnTheListedVariantsWithAppearanceChannels) {
  EvaluationOptions options;
  options.methods = {std::string(kProductMethod), std::string(Product().engine)};
  options.variants = {DescriptorVariant::kCeddLire, DescriptorVariant::kCeddHsvLayout};
  options.distortions = {ParseDistortionSpec("mb")};
  options.query_lengths = {2};
  options.trials = 2;
  options.engine = Product().options;
  const EvaluationReport report =
      RunEvaluation(ListCoil100(testing::CoilDir(), std::vector<int>{1, 2, 3, 4}), {}, options);

  // lire: the engine; layout and the product's own variant (added): product and the engine.
  ASSERT_EQ(report.cells.size(), 5u);
  std::map<std::pair<std::string, DescriptorVariant>, const EvaluationCell*> cells;
  for (const EvaluationCell& cell : report.cells) cells[{cell.method, cell.variant}] = &cell;
  const std::string product(kProductMethod), engine(Product().engine);
  ASSERT_TRUE(cells.count({engine, DescriptorVariant::kCeddLire}));
  ASSERT_TRUE(cells.count({product, Product().variant}));
  ASSERT_TRUE(cells.count({product, DescriptorVariant::kCeddHsvLayout}));
  ASSERT_TRUE(cells.count({engine, DescriptorVariant::kCeddHsvLayout}));
  const EvaluationCell& product_on_layout = *cells[{product, DescriptorVariant::kCeddHsvLayout}];
  EXPECT_EQ(product_on_layout.trials, 4 * 2);
  const EvaluationCell& engine_on_layout = *cells[{engine, DescriptorVariant::kCeddHsvLayout}];
  EXPECT_EQ(product_on_layout.hits, engine_on_layout.hits);
}

// The decisions of every query in `cell`, in order.
std::vector<Decision> DecisionsOf(const EvaluationCell& cell) {
  std::vector<Decision> decisions;
  for (const QueryVerdict& verdict : cell.verdicts) decisions.push_back(verdict.decision);
  return decisions;
}

// On each variant the product takes that variant's target rate, as a server does on a store
// made in it (ProductFalseAcceptRate), unless the run gives one. The engine beside it runs with
// the product's options at the layout's rate throughout: its decisions match the product's on
// the layout query by query, and on the product's own variant, where the rates differ, some do
// not. (The known share is off, so that the target alone places the threshold.)
TEST(RunEvaluationTest, ProductTakesEachVariantsOwnTargetRateUnlessTheRunGivesOne) {
  ASSERT_NE(ProductFalseAcceptRate(DescriptorVariant::kCeddHsvLayout),
            ProductFalseAcceptRate(Product().variant));
  EvaluationOptions options;
  options.methods = {std::string(kProductMethod), std::string(Product().engine)};
  options.variants = {DescriptorVariant::kCeddHsvLayout};
  options.distortions = {ParseDistortionSpec("df")};
  options.query_lengths = {1};
  options.trials = 3;
  options.engine = Product().options;
  options.engine.false_accept_rate = ProductFalseAcceptRate(DescriptorVariant::kCeddHsvLayout);
  options.engine.known_accept_rate = 0;
  // Look-alikes, whose windows' p-values spread between the two rates: eth-80-dev's objects
  // numbered 1-7 known, the 13 others unknown (apples, cows and cups 8-10; cars 9, 11, 12, 14).
  std::vector<DatasetImage> known, unknown;
  for (DatasetImage& image : ReadManifest(testing::DataDir() / "eth-80-dev" / "ring.csv")) {
    const int number = std::stoi(image.object.substr(image.object.find_first_of("0123456789")));
    (number <= 7 ? known : unknown).push_back(std::move(image));
  }
  // The cell of `method` on `variant`.
  const auto cell = [](const EvaluationReport& report, std::string_view method,
                       DescriptorVariant variant) {
    for (const EvaluationCell& c : report.cells) {
      if (c.method == method && c.variant == variant) return c;
    }
    ADD_FAILURE() << method << " has no cell on " << VariantName(variant);
    return EvaluationCell{};
  };
  const std::string_view product = kProductMethod, engine = Product().engine;
  const DescriptorVariant layout = DescriptorVariant::kCeddHsvLayout, own = Product().variant;

  EvaluationReport report = RunEvaluation(known, unknown, options);
  ASSERT_EQ(report.cells.size(), 4u);
  EXPECT_EQ(cell(report, product, layout).unknown_trials, 13 * 3);
  EXPECT_EQ(DecisionsOf(cell(report, product, layout)), DecisionsOf(cell(report, engine, layout)));
  EXPECT_NE(DecisionsOf(cell(report, product, own)), DecisionsOf(cell(report, engine, own)))
      << "the product on its own variant ran at the layout's rate";

  // A rate given for the run is the product's on every variant.
  options.product_false_accept_rate = options.engine.false_accept_rate;
  report = RunEvaluation(known, unknown, options);
  EXPECT_EQ(DecisionsOf(cell(report, product, own)), DecisionsOf(cell(report, engine, own)));
}

// --distractors: the queries are the dataset's alone (the same counts per cell), the report
// says how many objects joined the model set, and the product still finds COIL-100's objects
// among them on clean frames. Each verdict names its query's object and the object answered,
// by the model set's names: a known query's own, and for the unknown object 50 one of the three
// or a distractor, by its generated name.
TEST(RunEvaluationTest, DistractorsJoinTheModelSetButNotTheQueries) {
  EvaluationOptions options;
  options.methods = {std::string(kProductMethod)};
  options.variants = {Product().variant};
  options.distortions = {ParseDistortionSpec("df")};
  options.query_lengths = {4};
  options.trials = 2;
  options.distractors = 4;
  const EvaluationReport report =
      RunEvaluation(ListCoil100(testing::CoilDir(), std::vector<int>{1, 2, 3}),
                    ListCoil100(testing::CoilDir(), std::vector<int>{50}), options);
  EXPECT_EQ(report.distractors, 4u);
  ASSERT_EQ(report.cells.size(), 1u);
  EXPECT_EQ(report.cells[0].trials, 3 * 2);
  EXPECT_EQ(report.cells[0].hits, 3 * 2);
  EXPECT_EQ(report.cells[0].unknown_trials, 2);
  EXPECT_EQ(report.memory[0].objects, 3u);  // the known objects' memory alone
  ASSERT_EQ(report.cells[0].verdicts.size(), 3u * 2 + 2);
  for (const QueryVerdict& verdict : report.cells[0].verdicts) {
    if (verdict.known) {
      EXPECT_THAT(verdict.object, ::testing::AnyOf("obj1", "obj2", "obj3"));
      EXPECT_EQ(verdict.answer, verdict.object);
    } else {
      EXPECT_EQ(verdict.object, "obj50");
      EXPECT_THAT(verdict.answer, ::testing::AnyOf("obj1", "obj2", "obj3", "distractor1",
                                                   "distractor2", "distractor3", "distractor4"));
    }
  }
  options.distractors = kMaxDistractors + 1;
  EXPECT_EQ(testing::ErrorMessageOf([&] {
              RunEvaluation(ListCoil100(testing::CoilDir(), std::vector<int>{1}), {}, options);
            }),
            "distractors must be in 0..100000, got 100001");
}

// --active: the same queries count (objects x trials per cell), frames come in capture order
// from the protocol's first two views, and the pose is judged at the last view taken.
TEST(RunEvaluationTest, ActiveQueriesTakeTheirViewsFromTheMethodsMoves) {
  EvaluationOptions options;
  options.methods = {"hmm"};
  options.distortions = {ParseDistortionSpec("df")};
  options.query_lengths = {2, 4};
  options.trials = 3;
  const std::vector<DatasetImage> known =
      ListCoil100(testing::CoilDir(), std::vector<int>{1, 2, 3});
  const std::vector<DatasetImage> unknown = ListCoil100(testing::CoilDir(), std::vector<int>{4});
  const EvaluationReport passive = RunEvaluation(known, unknown, options);
  options.active_step = 20;
  const EvaluationReport active = RunEvaluation(known, unknown, options);
  EXPECT_EQ(active.active_step, 20);
  ASSERT_EQ(active.cells.size(), passive.cells.size());
  for (std::size_t c = 0; c < active.cells.size(); ++c) {
    EXPECT_EQ(active.cells[c].trials, 9);
    EXPECT_EQ(active.cells[c].unknown_trials, 3);
    for (const QueryVerdict& v : active.cells[c].verdicts) {
      if (v.hit) {
        EXPECT_FALSE(std::isnan(v.pose_error));
      }
    }
  }
  // n = 2 is the protocol's own two views either way: the same answers.
  EXPECT_EQ(active.cells[0].n, 2);
  EXPECT_EQ(active.cells[0].hits, passive.cells[0].hits);
  EXPECT_EQ(active.cells[0].rejected, passive.cells[0].rejected);
  // Three distinct known objects of COIL-100 are told apart after four active views.
  EXPECT_EQ(active.cells[1].n, 4);
  EXPECT_EQ(active.cells[1].hits, 9);
  // The control steps on one way whatever the moves say: the same first two views again.
  options.active_policy = ActivePolicy::kOneWay;
  const EvaluationReport control = RunEvaluation(known, unknown, options);
  EXPECT_EQ(control.active_policy, ActivePolicy::kOneWay);
  EXPECT_EQ(control.cells[0].hits, passive.cells[0].hits);
  EXPECT_EQ(control.cells[1].trials, 9);
}

// The oracle tries both ways at every step and keeps the best path for the truth: never worse
// than following the suggestion or stepping one way, query for query, and the same at n = 2
// (no step taken).
TEST(RunEvaluationTest, TheActiveOracleBoundsEveryLeftRightPolicy) {
  EvaluationOptions options;
  options.methods = {"hmm"};
  options.distortions = {ParseDistortionSpec("mb:len=25:angle=30")};
  options.query_lengths = {2, 4};
  options.trials = 4;
  options.active_step = 20;
  const std::vector<DatasetImage> known =
      ListCoil100(testing::CoilDir(), std::vector<int>{1, 2, 3, 4, 5, 6});
  const auto run = [&](ActivePolicy policy) {
    options.active_policy = policy;
    return RunEvaluation(known, {}, options);
  };
  const EvaluationReport follow = run(ActivePolicy::kFollowMoves);
  const EvaluationReport one_way = run(ActivePolicy::kOneWay);
  const EvaluationReport oracle = run(ActivePolicy::kBestOfBoth);
  ASSERT_EQ(oracle.cells.size(), 2u);
  EXPECT_EQ(oracle.cells[0].hits, follow.cells[0].hits);
  for (std::size_t q = 0; q < oracle.cells[1].verdicts.size(); ++q) {
    const bool best = oracle.cells[1].verdicts[q].hit;
    EXPECT_GE(best, follow.cells[1].verdicts[q].hit) << "query " << q;
    EXPECT_GE(best, one_way.cells[1].verdicts[q].hit) << "query " << q;
  }
  EXPECT_GE(oracle.cells[1].hits, std::max(follow.cells[1].hits, one_way.cells[1].hits));
  std::cout << "n = 4 hits of " << oracle.cells[1].trials << ": follow " << follow.cells[1].hits
            << ", one way " << one_way.cells[1].hits << ", oracle " << oracle.cells[1].hits << "\n";
}

// Captured sequences against a model set: objects 1-3 of COIL-100 every 10 degrees are the
// models; the queries are views in between (5, 15, ... degrees: images the model set does not
// hold) of objects 1 and 2, and of object 9, which is not in the model set.
TEST(RunCaptureEvaluationTest, EachSequenceIsOneQueryAskedWithItsFirstNFrames) {
  std::vector<DatasetImage> known;
  for (const DatasetImage& image : ListCoil100(testing::CoilDir(), std::vector<int>{1, 2, 3})) {
    if (static_cast<int>(image.azimuth) % 10 == 0) known.push_back(image);
  }
  const auto frame = [](int object, int azimuth, const std::string& sequence) {
    return CaptureFrame{(testing::DataDir() / "coil-100" /
                         ("obj" + std::to_string(object) + "__" + std::to_string(azimuth) + ".png"))
                            .string(),
                        "obj" + std::to_string(object), double(azimuth), sequence};
  };
  const std::vector<CaptureFrame> captures{
      frame(1, 5, "a"),   frame(1, 15, "a"), frame(1, 25, "a"), frame(2, 105, "b"),
      frame(2, 115, "b"), frame(9, 5, "c"),  frame(9, 15, "c")};
  EvaluationOptions options;
  options.methods = {std::string(kProductMethod)};
  options.variants = {Product().variant};
  options.distortions = {ParseDistortionSpec("df")};
  options.query_lengths = {1, 3};

  const EvaluationReport report = RunCaptureEvaluation(known, captures, options);
  EXPECT_EQ(report.query_sequences, 3u);
  EXPECT_EQ(report.query_frames, 7u);
  EXPECT_EQ(report.known_objects, 3u);
  EXPECT_EQ(report.unknown_objects, 1u);
  EXPECT_EQ(report.memory.at(0).views, 3u * 36);  // every model image, nothing left out
  ASSERT_EQ(report.cells.size(), 2u);
  // n = 1: sequences a and b (known), c (unknown); n = 3: only a is long enough.
  EXPECT_EQ(report.cells[0].n, 1);
  EXPECT_EQ(report.cells[0].trials, 2);
  EXPECT_EQ(report.cells[0].unknown_trials, 1);
  EXPECT_EQ(report.cells[0].hits, 2);  // clean views 5 degrees from a model view
  EXPECT_EQ(report.cells[1].n, 3);
  EXPECT_EQ(report.cells[1].trials, 1);
  EXPECT_EQ(report.cells[1].unknown_trials, 0);
  EXPECT_EQ(report.cells[1].hits, 1);

  std::vector<CaptureFrame> mixed = captures;
  mixed[1].object = "obj2";
  EXPECT_EQ(testing::ErrorMessageOf([&] { RunCaptureEvaluation(known, mixed, options); }),
            "sequence \"a\" shows two objects (\"obj1\" and \"obj2\")");
}

// Captured frames are described in their boxes, as the model views are: eth-80-dev's ring views
// of apple1 and cup1, cut to their boxes, are the models, and the captures are two of those
// very images, one a sequence. Each frame cut to its box is then its own model view, matched
// exactly (U = 0); described whole, as frames were before boxes reached the captures, it matches no
// view exactly.
TEST(RunCaptureEvaluationTest, FramesAreDescribedInTheirBoxesAsTheModelViewsAre) {
  const std::filesystem::path eth = testing::DataDir() / "eth-80-dev";
  const std::map<std::string, ImageBox> boxes = ReadBoxes(eth / "boxes.csv");
  std::vector<DatasetImage> known;
  for (DatasetImage& image : ReadManifest(eth / "ring.csv")) {
    if (image.object == "apple1" || image.object == "cup1") known.push_back(std::move(image));
  }
  ASSERT_EQ(known.size(), 32u);
  AttachBoxes(known, boxes, kDefaultBoxMargin);
  std::vector<CaptureFrame> captures;
  for (const std::size_t i : {0u, 16u}) {
    captures.push_back({known[i].path, known[i].object, known[i].azimuth, known[i].object});
  }
  EvaluationOptions options;
  options.methods = {std::string(kProductMethod)};
  options.variants = {Product().variant};
  options.distortions = {ParseDistortionSpec("df")};
  options.query_lengths = {1};

  const auto statistics = [&](const EvaluationOptions& o) {
    const EvaluationReport report = RunCaptureEvaluation(known, captures, o);
    std::vector<double> u;
    for (const QueryVerdict& verdict : report.cells.at(0).verdicts) {
      EXPECT_TRUE(verdict.hit) << verdict.object;
      u.push_back(verdict.unknown_statistic);
    }
    return u;
  };
  options.boxes = boxes;
  EXPECT_THAT(statistics(options), ::testing::ElementsAre(0.0, 0.0));
  options.boxes.clear();
  EXPECT_THAT(statistics(options), ::testing::ElementsAre(::testing::Gt(0.0), ::testing::Gt(0.0)));
}

}  // namespace
}  // namespace orbit
