// build/orbit_coil_variants: a larger model set made from COIL-100, for measuring the server at
// 1000 objects (docs/results/load.md; scripts/loadtest.sh with OBJECTS=1000).
//
//   orbit_coil_variants COIL_DIR OUT_DIR [COPIES]      COPIES in 1..10, default 10
//
// Writes COPIES x 100 objects into OUT_DIR in COIL-100's layout (objN__A.png), so that
// `orbit import --layout coil100 --data OUT_DIR` enrolls them as any dataset is enrolled:
//   copy 0, objects 1-100:        links to COIL_DIR's own images;
//   copy k, objects 100k+1..100k+100: every view of object n with its colour channels permuted
//                                 and the image turned by a multiple of 90 degrees (kVariants).
// A copy is a different-looking object with COIL-100's statistics: the permutation moves its
// colours into other CEDD colour bins and the turn moves its edges into other texture classes,
// so no two objects share descriptors and a session's candidates are as many as they would be
// with 1000 real objects. Files already in OUT_DIR are kept, so an interrupted run resumes.
#include <array>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "evaluation/dataset.h"

namespace {

struct Variant {
  std::array<int, 3> channels;  // source channel of each output channel (BGR)
  int quarter_turns;            // clockwise, 0..3
};

// Copies 1..9; copy 0 is the original. Every copy differs from the others in at least one of the
// two transforms.
constexpr std::array<Variant, 9> kVariants{{
    {{1, 2, 0}, 0},
    {{2, 0, 1}, 0},
    {{0, 2, 1}, 0},
    {{2, 1, 0}, 0},
    {{1, 0, 2}, 0},
    {{0, 1, 2}, 1},
    {{1, 2, 0}, 2},
    {{2, 0, 1}, 3},
    {{2, 1, 0}, 1},
}};

cv::Mat Transform(const cv::Mat& image, const Variant& variant) {
  std::vector<cv::Mat> planes;
  cv::split(image, planes);
  cv::Mat permuted;
  cv::merge(std::vector<cv::Mat>{planes[variant.channels[0]], planes[variant.channels[1]],
                                 planes[variant.channels[2]]},
            permuted);
  if (variant.quarter_turns == 0) return permuted;
  static constexpr std::array<int, 3> kTurn{cv::ROTATE_90_CLOCKWISE, cv::ROTATE_180,
                                            cv::ROTATE_90_COUNTERCLOCKWISE};
  cv::Mat turned;
  cv::rotate(permuted, turned, kTurn[variant.quarter_turns - 1]);
  return turned;
}

std::string FileName(int object, double azimuth) {
  return "obj" + std::to_string(object) + "__" + std::to_string(static_cast<int>(azimuth)) + ".png";
}

}  // namespace

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  if (argc < 3 || argc > 4) {
    std::fprintf(stderr, "usage: %s COIL_DIR OUT_DIR [COPIES (1..10, default 10)]\n", argv[0]);
    return 2;
  }
  const fs::path coil_dir = argv[1];
  const fs::path out_dir = argv[2];
  const int copies = argc == 4 ? std::atoi(argv[3]) : 10;
  if (copies < 1 || copies > static_cast<int>(kVariants.size()) + 1) {
    std::fprintf(stderr, "COPIES must be in 1..10, not '%s'\n", argv[3]);
    return 2;
  }
  try {
    const std::vector<orbit::DatasetImage> images = orbit::ListCoil100(coil_dir);
    fs::create_directories(out_dir);
    const std::size_t total = images.size() * static_cast<std::size_t>(copies);
    std::size_t done = 0;
    for (const orbit::DatasetImage& image : images) {
      const int object = std::stoi(image.object.substr(3));  // "objN"
      if (object > 100) throw std::runtime_error(image.path + ": COIL-100 numbers objects 1-100");
      const fs::path original = out_dir / FileName(object, image.azimuth);
      if (!fs::exists(fs::symlink_status(original))) {
        fs::create_symlink(fs::absolute(image.path), original);
      }
      const cv::Mat pixels = copies > 1 ? cv::imread(image.path, cv::IMREAD_COLOR) : cv::Mat();
      if (copies > 1 && pixels.empty()) throw std::runtime_error(image.path + ": cannot read");
      for (int k = 1; k < copies; ++k) {
        const fs::path copy = out_dir / FileName(100 * k + object, image.azimuth);
        if (!fs::exists(copy) && !cv::imwrite(copy.string(), Transform(pixels, kVariants[k - 1]))) {
          throw std::runtime_error(copy.string() + ": cannot write");
        }
      }
      done += copies;
      if (done % 3600 < static_cast<std::size_t>(copies)) {
        std::fprintf(stderr, "\r%zu / %zu images", done, total);
      }
    }
    std::fprintf(stderr, "\r%zu / %zu images in %s\n", total, total, out_dir.c_str());
  } catch (const std::exception& error) {
    std::fprintf(stderr, "error: %s\n", error.what());
    return 1;
  }
  return 0;
}
