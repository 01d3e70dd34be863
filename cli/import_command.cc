// orbit import: turns a dataset of object views into a model store, one object per name, each
// enrolled in its own transaction (docs/design.md#overview: turning a dataset into a model
// set).
#include <unistd.h>

#include <functional>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "api/conversion.h"
#include "api/engines/conversion.h"
#include "cli/box_arguments.h"
#include "cli/commands.h"
#include "cli/enrollment_report_text.h"
#include "cli/network_options.h"
#include "cli/progress_bar.h"
#include "client/enroller.h"
#include "client/models_client.h"
#include "client/rpc_error.h"
#include "core/base/parallel_for.h"
#include "core/decision/enrollment_feedback.h"
#include "core/descriptor/view_description.h"
#include "core/engines/product_pipeline.h"
#include "evaluation/dataset.h"
#include "evaluation/distractor_objects.h"
#include "storage/model_validation.h"
#include "storage/sqlite_model_store.h"
#include "storage/view_index_loading.h"

namespace orbit::cli {
namespace {

struct ImportOptions {
  std::string db;
  NetworkOptions network;
  std::string layout;
  std::string data;
  std::string objects;
  std::string manifest;
  std::string boxes;  // boxes.csv: describe each image's object region instead of the whole image
  double box_margin = kDefaultBoxMargin;
  std::string variant;  // "": the store's (the product's for a new one); the server's with --server
  std::uint64_t seed = kDefaultViewNoiseSeed;
  unsigned threads = static_cast<unsigned>(AvailableCpus());
};

// The model views of one object (its images are positions in `images`), each image (its
// object's region, when it has a box) described as every enrollment path describes it
// (core/descriptor/view_description.h: CEDD and typical distance, `seed` the base of the seed
// rule), on `threads` threads. The numbers depend on the images alone, whatever the thread count.
std::vector<ModelView> ComputeViews(const std::vector<DatasetImage>& images,
                                    const DatasetObject& object, DescriptorVariant variant,
                                    std::uint64_t seed, unsigned threads) {
  std::vector<ModelView> views(object.images.size());
  ParallelFor(views.size(), static_cast<int>(threads), [&](std::size_t f) {
    const DatasetImage& image = images[object.images[f]];
    const ViewDescription described = DescribeView(ReadDescribedRegion(image), variant, seed);
    views[f] = {described.descriptor, image.azimuth, image.elevation, described.typical_distance};
  });
  return views;
}

// Where the objects go: a model store file (--db) or a server (--server), which enrolls each
// object atomically too.
struct ImportTarget {
  DescriptorVariant variant = DescriptorVariant::kCeddLire;
  std::string where;        // "in the store" / "on the server", for skipped objects
  std::string destination;  // "in FILE" / "on HOST:PORT", for the summary
  std::function<std::optional<ObjectId>(const std::string& name)> find;
  // Enrolls the object; returns its id and what the enrollment got.
  std::function<std::pair<ObjectId, v1::EnrollmentReport>(const Enrollment& enrollment)> enroll;
};

ImportTarget StoreTarget(const ImportOptions& options) {
  SqliteModelStoreOptions store_options;
  store_options.create_if_missing = true;
  auto store = std::make_shared<SqliteModelStore>(options.db, store_options);
  ImportTarget target;
  // The store's variant (a server refuses a store of mixed variants), the product's for a new
  // store, unless --variant says otherwise.
  const std::optional<DescriptorVariant> stored = StoreVariant(*store);
  target.variant =
      options.variant.empty() ? stored.value_or(Product().variant) : *ParseVariant(options.variant);
  if (stored && *stored != target.variant) {
    throw std::invalid_argument("--variant " + options.variant + " is not the variant of the " +
                                "objects in " + options.db + " (" +
                                std::string(VariantName(*stored)) + "); variants cannot be mixed");
  }
  target.where = "in the store";
  target.destination = "in " + options.db;
  target.find = [store](const std::string& name) -> std::optional<ObjectId> {
    if (std::optional<ObjectSummary> existing = store->Find(name)) return existing->id;
    return std::nullopt;
  };
  // The store's objects indexed, to report on each new one against those before it, in the
  // server's search mode: a large store's report then comes from the candidates a server would
  // propose, found by the summary graphs instead of a scan of every summary
  // (docs/design.md#enrollment-feedback).
  std::shared_ptr<ViewIndex> index = LoadViewIndex(
      *store, target.variant, {.search = SearchMode::kKdTree, .build_threads = AvailableCpus()});
  target.enroll = [store, index](const Enrollment& enrollment) {
    ObjectModel model{store->Enroll(enrollment), enrollment.name, enrollment.variant,
                      enrollment.views};
    index->Add(model);
    const std::shared_ptr<const ViewIndexSnapshot> snapshot = index->Snapshot();
    return std::make_pair(model.id,
                          ToEnrollmentReport(AssessEnrollment(model, *snapshot), *snapshot));
  };
  return target;
}

ImportTarget ServerTarget(const ImportOptions& options) {
  auto connection = std::make_shared<Connection>(ToConnectionOptions(options.network));
  auto enroller = std::make_shared<Enroller>(*connection);
  ImportTarget target;
  target.variant = enroller->variant();
  if (!options.variant.empty() && *ParseVariant(options.variant) != target.variant) {
    throw std::invalid_argument("--variant " + options.variant + " is not the server's (" +
                                std::string(VariantName(target.variant)) + ")");
  }
  target.where = "on the server";
  target.destination = "on " + options.network.server;
  target.find = [connection](const std::string& name) -> std::optional<ObjectId> {
    try {
      return ModelsClient(*connection).GetObject(ObjectByName(name)).object().id();
    } catch (const RpcError& e) {
      if (e.code() == grpc::StatusCode::NOT_FOUND) return std::nullopt;
      throw;
    }
  };
  // `connection` is captured so that it outlives the enroller that refers to it.
  target.enroll = [connection, enroller](const Enrollment& enrollment) {
    std::vector<v1::View> views;
    for (const ModelView& view : enrollment.views)
      views.push_back(ToProtoView(view, enrollment.variant));
    const v1::ObjectInfo object = enroller->EnrollViews(enrollment.name, views);
    return std::make_pair(object.id(), object.report());
  };
  return target;
}

// One object to import: its name, and how its views are computed in a variant.
struct ImportObject {
  std::string name;
  std::function<std::vector<ModelView>(DescriptorVariant)> views;
};

// The objects of a dataset on disk (--layout coil100 or manifest), every name and every box
// checked before anything is computed or written.
std::vector<ImportObject> DatasetObjects(const ImportOptions& options) {
  auto images = std::make_shared<std::vector<DatasetImage>>(
      SelectDataset({options.layout, options.data, options.manifest, options.objects, ""}).known);
  if (!options.boxes.empty()) AttachBoxes(*images, ReadBoxes(options.boxes), options.box_margin);
  SetBoxMargin(*images, options.box_margin);
  std::vector<ImportObject> objects;
  for (DatasetObject& object : GroupByObject(*images)) {
    ValidateObjectName(object.name);
    auto grouped = std::make_shared<DatasetObject>(std::move(object));
    objects.push_back({grouped->name, [images, grouped, &options](DescriptorVariant variant) {
                         return ComputeViews(*images, *grouped, variant, options.seed,
                                             options.threads);
                       }});
  }
  CheckBoxes(*images);
  return objects;
}

// The generated objects --objects selects (--layout distractors): distractor<k> of the
// distractors drawn from --seed, as `orbit eval --distractors` adds them.
std::vector<ImportObject> GeneratedObjects(const ImportOptions& options) {
  if (options.objects.empty()) {
    throw std::invalid_argument("--layout distractors needs --objects, e.g. 1-10000 (at most " +
                                std::to_string(kMaxDistractors) + ")");
  }
  const std::vector<int> numbers = ParseObjectRange(options.objects);
  if (numbers.back() > kMaxDistractors) {
    throw std::invalid_argument("--objects: distractor numbers are 1.." +
                                std::to_string(kMaxDistractors) + ", got " +
                                std::to_string(numbers.back()));
  }
  auto distractors =
      std::make_shared<const DistractorObjects>(options.seed, static_cast<int>(options.threads));
  std::vector<ImportObject> objects;
  for (const int k : numbers) {
    objects.push_back({DistractorObjects::Name(k), [distractors, k, &options](DescriptorVariant v) {
                         return distractors->Views(k, v, static_cast<int>(options.threads));
                       }});
  }
  return objects;
}

int RunImport(const ImportOptions& options) {
  const bool remote = UsesServer(options.db, options.network);
  const std::vector<ImportObject> objects =
      options.layout == "distractors" ? GeneratedObjects(options) : DatasetObjects(options);
  const ImportTarget target = remote ? ServerTarget(options) : StoreTarget(options);
  const DescriptorVariant variant = target.variant;

  const bool terminal = ::isatty(STDERR_FILENO) == 1;
  ProgressBar progress(std::cerr, terminal);
  std::size_t enrolled = 0;
  std::size_t skipped = 0;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const ImportObject& object = objects[i];
    progress.Update("import", i, objects.size());
    if (std::optional<ObjectId> existing = target.find(object.name)) {
      // An import that was interrupted carries on where it stopped.
      std::cout << "skipped " << object.name << " (already " << target.where << " as id "
                << *existing << ")\n";
      ++skipped;
      continue;
    }
    Enrollment enrollment;
    enrollment.name = object.name;
    enrollment.variant = variant;
    enrollment.views = object.views(variant);
    const auto [id, report] = target.enroll(enrollment);
    // Printed only once the object is durable: a line here is a promise.
    std::cout << "enrolled " << object.name << " (id " << id << ", " << enrollment.views.size()
              << " views)\n"
              << EnrollmentReportText(report) << std::flush;
    ++enrolled;
  }
  progress.Update("import", objects.size(), objects.size());
  std::cerr << "orbit import: " << enrolled << " objects enrolled, " << skipped
            << " already present, " << target.destination << "\n";
  return 0;
}

}  // namespace

void AddImportCommand(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<ImportOptions>();
  CLI::App* command = app.add_subcommand(
      "import",
      "Compute the descriptors of a dataset's images and enroll one object per name in a model\n"
      "store (--db, created if missing) or on a server (--server; admin token), each object in\n"
      "its own transaction. Prints one line per\n"
      "object once it is durable; objects already in the store are skipped, so an interrupted\n"
      "import resumes when run again. Progress goes to stderr.");
  AddDatabaseOrServerOptions(*command, options->db, options->network);
  command
      ->add_option("--layout", options->layout,
                   "coil100: objN__A.png files in --data;\n"
                   "manifest: a CSV file (--manifest);\n"
                   "distractors: generated boxes and cylinders with patterned faces, 72 views\n"
                   "each (the objects `orbit eval --distractors` adds; --objects selects them)")
      ->required()
      ->check(CLI::IsMember({"coil100", "manifest", "distractors"}));
  command->add_option("--data", options->data, "folder of COIL-100 images (--layout coil100)");
  command->add_option("--objects", options->objects,
                      "objects to import, e.g. 1-20 or 1-5,9 (coil100: object numbers;\n"
                      "manifest: order of first appearance; distractors: their numbers,\n"
                      "required); default: all");
  command->add_option("--manifest", options->manifest,
                      "CSV with columns path,object,azimuth[,elevation][,x,y,w,h: the object's "
                      "box] (--layout manifest)");
  command->add_option("--boxes", options->boxes,
                      "CSV with columns path,x,y,w,h (a dataset's boxes.csv): describe each\n"
                      "image's object, its box grown by --box-margin, instead of the whole image");
  AddBoxMarginOption(*command, options->box_margin);
  command
      ->add_option("--variant", options->variant,
                   "descriptor variant (default: that of the store's objects, " +
                       std::string(VariantName(Product().variant)) +
                       " for a new store; with --server, the server's)")
      ->check(CLI::IsMember(VariantNames()));
  command
      ->add_option("--seed", options->seed,
                   "base seed of the noisy copies for typical distances (the default stores\n"
                   "what a server or the client library computes from the same images)")
      ->capture_default_str();
  command->add_option("--threads", options->threads, "threads computing descriptors")
      ->check(CLI::Range(1u, 256u))
      ->capture_default_str();
  command->callback([options, &exit_code] { exit_code = RunImport(*options); });
}

}  // namespace orbit::cli
