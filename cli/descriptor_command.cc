// orbit descriptor: prints the CEDD descriptor of image files, one line per image.
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "client/image_file.h"
#include "core/descriptor/cedd.h"

namespace orbit::cli {
namespace {

struct DescriptorOptions {
  std::string variant = "cedd-lire";
  std::vector<std::string> files;
};

// Prints `FILE v0 ... v143` for each readable image; a file that cannot be read gets a message on
// stderr, the others are still processed, and the exit code is 1.
int RunDescriptor(const DescriptorOptions& options) {
  const DescriptorVariant variant = *ParseVariant(options.variant);
  int failures = 0;
  std::string line;
  for (const std::string& file : options.files) {
    try {
      const Descriptor descriptor = ExtractCedd(ReadImageFile(file), variant);
      line = file;
      for (std::uint8_t v : DescriptorBytes(descriptor.values, variant)) {
        line += ' ';
        line += static_cast<char>('0' + v);
      }
      line += '\n';
      std::cout << line;
    } catch (const std::exception& e) {
      std::cout.flush();
      std::cerr << "orbit descriptor: " << e.what() << "\n";
      ++failures;
    }
  }
  if (failures > 0) {
    std::cerr << "orbit descriptor: " << failures << " of " << options.files.size()
              << " files failed\n";
  }
  return failures > 0 ? 1 : 0;
}

}  // namespace

void AddDescriptorCommand(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<DescriptorOptions>();
  CLI::App* command = app.add_subcommand(
      "descriptor",
      "Print the descriptor of each image: one line per file, `FILE v0 v1 ... v143` (v479 in\n"
      "the variants with appearance channels: CEDD, then those channels), values 0..7 "
      "(docs/design.md). A file "
      "that cannot be read is reported on stderr and\n"
      "makes the exit status 1; the other files are still processed.");
  command
      ->add_option("--variant", options->variant,
                   "cedd-lire: bit-exact with LIRE (reads only LIRE's block grid);\n"
                   "cedd-full: a 40x40 grid covering every pixel;\n"
                   "cedd-robust: cedd-full of the canonical frame;\n"
                   "cedd-hsv-hog: cedd-robust, then a colour histogram and gradient cells of the\n"
                   "same frame, its background's colours taken off;\n"
                   "cedd-hsv-layout: cedd-hsv-hog with the object's colours in the frame's\n"
                   "upper and lower halves instead of one colour histogram;\n"
                   "cedd-soft-hsv-hog: cedd-hsv-hog with a hue near a colour bin's edge shared\n"
                   "with the bin beyond, and its own channel weights (the product's variant)")
      ->check(CLI::IsMember(VariantNames()))
      ->capture_default_str();
  command->add_option("FILE", options->files, "image files (PNG, JPEG, ...)")->required();
  command->callback([options, &exit_code] { exit_code = RunDescriptor(*options); });
}

}  // namespace orbit::cli
