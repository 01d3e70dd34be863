// orbit import: turns a dataset of object views into a model store, one object per name, each
// enrolled in its own transaction (SPEC.md, "Users and their jobs": import a dataset as a model
// set).
#include <unistd.h>

#include <algorithm>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "client/cli/commands.h"
#include "client/dataset.h"
#include "client/image_file.h"
#include "client/progress_bar.h"
#include "core/cedd.h"
#include "core/typical_distance.h"
#include "storage/model_validation.h"
#include "storage/sqlite_model_store.h"

namespace orbit::cli {
namespace {

struct ImportOptions {
  std::string db;
  std::string layout;
  std::string data;
  std::string objects;
  std::string manifest;
  std::string variant = "cedd-lire";
  std::uint64_t seed = 1;
  unsigned threads = std::max(1u, std::thread::hardware_concurrency());
};

// The images of one object, in dataset order; `first_image` is the position of the first one in
// the whole dataset listing (it seeds each view's noisy copy).
struct ObjectImages {
  std::string name;
  std::vector<DatasetImage> images;
  std::size_t first_image = 0;
};

std::vector<DatasetImage> ListImages(const ImportOptions& options) {
  if (options.layout == "coil100") {
    if (options.data.empty()) throw std::invalid_argument("--layout coil100 needs --data DIR");
    std::optional<std::vector<int>> objects;
    if (!options.objects.empty()) objects = ParseObjectRange(options.objects);
    return ListCoil100(options.data, objects);
  }
  if (options.manifest.empty()) throw std::invalid_argument("--layout manifest needs --manifest");
  if (!options.objects.empty()) {
    throw std::invalid_argument("--objects applies to --layout coil100 only");
  }
  return ReadManifest(options.manifest);
}

// Groups the images by object name, objects in order of first appearance. Every name is checked
// before anything is computed or written.
std::vector<ObjectImages> GroupByObject(const std::vector<DatasetImage>& images) {
  std::vector<ObjectImages> objects;
  for (std::size_t i = 0; i < images.size(); ++i) {
    auto same_name = [&](const ObjectImages& o) { return o.name == images[i].object; };
    auto found = std::find_if(objects.begin(), objects.end(), same_name);
    if (found == objects.end()) {
      ValidateObjectName(images[i].object);
      found = objects.insert(objects.end(), ObjectImages{images[i].object, {}, i});
    }
    found->images.push_back(images[i]);
  }
  return objects;
}

// The model views of one object: CEDD and typical distance (SPEC.md, "Recognition") of each
// image, computed on `threads` threads. View f's noisy copy is seeded with seed + its position
// in the dataset, so an import is reproducible whatever the thread count.
std::vector<ModelView> ComputeViews(const ObjectImages& object, DescriptorVariant variant,
                                    std::uint64_t seed, unsigned threads) {
  std::vector<ModelView> views(object.images.size());
  std::vector<std::string> errors(threads);
  auto work = [&](unsigned worker) {
    try {
      for (std::size_t f = worker; f < views.size(); f += threads) {
        const DatasetImage& image = object.images[f];
        const cv::Mat pixels = ReadImageFile(image.path);
        views[f].descriptor = ExtractCedd(pixels, variant).values;
        views[f].azimuth = image.azimuth;
        views[f].elevation = image.elevation;
        views[f].typical_distance = TypicalDistance(pixels, variant, seed + object.first_image + f);
      }
    } catch (const std::exception& e) {
      errors[worker] = e.what();
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work, t);
  work(0);
  for (std::thread& thread : pool) thread.join();
  for (const std::string& error : errors) {
    if (!error.empty()) throw std::runtime_error(error);
  }
  return views;
}

int RunImport(const ImportOptions& options) {
  const DescriptorVariant variant = *ParseVariant(options.variant);
  const std::vector<ObjectImages> objects = GroupByObject(ListImages(options));
  SqliteModelStore store(options.db, {.create_if_missing = true});

  const bool terminal = ::isatty(STDERR_FILENO) == 1;
  ProgressBar progress(std::cerr, terminal);
  std::size_t enrolled = 0;
  std::size_t skipped = 0;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const ObjectImages& object = objects[i];
    progress.Update("import", i, objects.size());
    if (std::optional<ObjectSummary> existing = store.Find(object.name)) {
      // An import that was interrupted carries on where it stopped.
      std::cout << "skipped " << object.name << " (already in the store as id " << existing->id
                << ")\n";
      ++skipped;
      continue;
    }
    Enrollment enrollment;
    enrollment.name = object.name;
    enrollment.variant = variant;
    enrollment.views = ComputeViews(object, variant, options.seed, options.threads);
    const ObjectId id = store.Enroll(enrollment);
    // Printed only once the object is durable: a line here is a promise.
    std::cout << "enrolled " << object.name << " (id " << id << ", " << enrollment.views.size()
              << " views)" << std::endl;
    ++enrolled;
  }
  progress.Update("import", objects.size(), objects.size());
  std::cerr << "orbit import: " << enrolled << " objects enrolled, " << skipped
            << " already present, in " << options.db << "\n";
  return 0;
}

}  // namespace

void AddImportCommand(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<ImportOptions>();
  CLI::App* command = app.add_subcommand(
      "import",
      "Compute the descriptors of a dataset's images and enroll one object per name in a model\n"
      "store (created if missing), each object in its own transaction. Prints one line per\n"
      "object once it is durable; objects already in the store are skipped, so an interrupted\n"
      "import resumes when run again. Progress goes to stderr.");
  command->add_option("--db", options->db, "model store file (SQLite)")->required();
  command->add_option("--layout", options->layout, "coil100: objN__A.png files in --data;\n"
                                                   "manifest: a CSV file (--manifest)")
      ->required()
      ->check(CLI::IsMember({"coil100", "manifest"}));
  command->add_option("--data", options->data, "folder of COIL-100 images (--layout coil100)");
  command->add_option("--objects", options->objects,
                      "COIL-100 objects to import, e.g. 1-20 or 1-5,9 (default: all)");
  command->add_option("--manifest", options->manifest,
                      "CSV with columns path,object,azimuth[,elevation] (--layout manifest)");
  command->add_option("--variant", options->variant, "descriptor variant")
      ->check(CLI::IsMember({"cedd-lire", "cedd-full"}))
      ->capture_default_str();
  command->add_option("--seed", options->seed, "seed of the noisy copies for typical distances")
      ->capture_default_str();
  command->add_option("--threads", options->threads, "threads computing descriptors")
      ->check(CLI::Range(1u, 256u))
      ->capture_default_str();
  command->callback([options, &exit_code] { exit_code = RunImport(*options); });
}

}  // namespace orbit::cli
