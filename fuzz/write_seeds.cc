// Writes the seed corpora of the fuzz targets, fuzz/corpus/<target>/: small valid inputs of
// every kind each target takes, and a few at the edges of what it accepts. The committed corpus
// was written by this program (plus the inputs the fuzzers found, named crash-* or timeout-*,
// which are kept as regression seeds); run it again after changing it:
//
//   cmake --build build --target write_seeds && build/fuzz/write_seeds fuzz/corpus
//
// Deterministic: the same program writes the same bytes.
#include <zlib.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <google/protobuf/util/delimited_message_util.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "orbit/v1/models.pb.h"
#include "orbit/v1/recognition.pb.h"

namespace {

namespace fs = std::filesystem;
using orbit::v1::EnrollRequest;
using orbit::v1::Frame;
using orbit::v1::RecognizeRequest;
using orbit::v1::SessionOptions;

fs::path corpus_root;

void Write(const std::string& target, const std::string& name, const std::string& bytes) {
  const fs::path folder = corpus_root / target;
  fs::create_directories(folder);
  std::ofstream out(folder / name, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// ---- images ----------------------------------------------------------------------------------

// A small image with some structure (a gradient, a bright square, noise) so that CEDD sees
// edges and colours.
cv::Mat Picture(int width, int height, int type) {
  cv::Mat image(height, width, type);
  cv::RNG rng(7);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      for (int c = 0; c < image.channels(); ++c) {
        int v = (x * 255 / std::max(1, width - 1) + c * 60 + rng.uniform(0, 20)) % 256;
        if (x > width / 3 && x < 2 * width / 3 && y > height / 3 && y < 2 * height / 3) v = 240;
        if (image.depth() == CV_16U) {
          image.ptr<std::uint16_t>(y)[x * image.channels() + c] =
              static_cast<std::uint16_t>(v * 257);
        } else {
          image.ptr<std::uint8_t>(y)[x * image.channels() + c] = static_cast<std::uint8_t>(v);
        }
      }
    }
  }
  return image;
}

std::string Encode(const std::string& extension, const cv::Mat& image,
                   const std::vector<int>& parameters = {}) {
  std::vector<std::uint8_t> bytes;
  if (!cv::imencode(extension, image, bytes, parameters)) {
    throw std::runtime_error("cannot encode " + extension);
  }
  return {bytes.begin(), bytes.end()};
}

std::string BigEndian32(std::uint32_t value) {
  return {static_cast<char>(value >> 24), static_cast<char>(value >> 16),
          static_cast<char>(value >> 8), static_cast<char>(value)};
}

std::string PngChunk(const std::string& type, const std::string& data) {
  const std::string body = type + data;
  const auto crc =
      crc32(0, reinterpret_cast<const Bytef*>(body.data()), static_cast<uInt>(body.size()));
  return BigEndian32(static_cast<std::uint32_t>(data.size())) + body +
         BigEndian32(static_cast<std::uint32_t>(crc));
}

const std::string kPngSignature = "\x89PNG\r\n\x1a\n";

// A PNG written by hand, for what OpenCV's encoder never writes (palettes, interlacing):
// `scanlines` is the filtered image data (each row a filter byte, then the row), compressed here.
std::string HandMadePng(std::uint32_t width, std::uint32_t height, int depth, int colour,
                        int interlace, const std::string& scanlines,
                        const std::string& palette = "") {
  uLongf size = compressBound(static_cast<uLong>(scanlines.size()));
  std::string compressed(size, '\0');
  compress(reinterpret_cast<Bytef*>(compressed.data()), &size,
           reinterpret_cast<const Bytef*>(scanlines.data()), static_cast<uLong>(scanlines.size()));
  compressed.resize(size);
  const std::string ihdr = BigEndian32(width) + BigEndian32(height) +
                           std::string{static_cast<char>(depth), static_cast<char>(colour), 0, 0,
                                       static_cast<char>(interlace)};
  std::string png = kPngSignature + PngChunk("IHDR", ihdr);
  if (!palette.empty()) png += PngChunk("PLTE", palette);
  return png + PngChunk("IDAT", compressed) + PngChunk("IEND", "");
}

std::string JpegSegment(std::uint8_t code, const std::string& data) {
  const auto length = static_cast<std::uint32_t>(data.size() + 2);
  return std::string{'\xff', static_cast<char>(code), static_cast<char>(length >> 8),
                     static_cast<char>(length)} +
         data;
}

void WriteImageSeeds() {
  const std::string t = "image_decode";
  Write(t, "png-rgb-16x12", Encode(".png", Picture(16, 12, CV_8UC3)));
  Write(t, "png-grey-9x7", Encode(".png", Picture(9, 7, CV_8UC1)));
  Write(t, "png-rgba-8x8", Encode(".png", Picture(8, 8, CV_8UC4)));
  Write(t, "png-16bit-rgb-6x5", Encode(".png", Picture(6, 5, CV_16UC3)));
  Write(t, "png-1x1", Encode(".png", Picture(1, 1, CV_8UC3)));
  // Palette (colour type 3) of 2 colours, 4x2 at 1 bit per pixel.
  Write(t, "png-palette-4x2",
        HandMadePng(4, 2, 1, 3, 0, std::string("\0\xa0", 2) + std::string("\0\x50", 2),
                    std::string("\xff\x00\x00\x00\x00\xff", 6)));
  // Grey and alpha (colour type 4), 2x1.
  Write(t, "png-grey-alpha-2x1", HandMadePng(2, 1, 8, 4, 0, std::string("\0\x80\xff\x10\x40", 5)));
  // Adam7-interlaced 1x1 RGB: only the first pass has a pixel.
  Write(t, "png-interlaced-1x1", HandMadePng(1, 1, 8, 2, 1, std::string("\0\x10\x20\x30", 4)));

  Write(t, "jpeg-colour-16x16",
        Encode(".jpg", Picture(16, 16, CV_8UC3), {cv::IMWRITE_JPEG_QUALITY, 50}));
  Write(t, "jpeg-grey-8x8", Encode(".jpg", Picture(8, 8, CV_8UC1), {cv::IMWRITE_JPEG_QUALITY, 50}));
  Write(t, "jpeg-progressive-16x8",
        Encode(".jpg", Picture(16, 8, CV_8UC3),
               {cv::IMWRITE_JPEG_PROGRESSIVE, 1, cv::IMWRITE_JPEG_QUALITY, 50}));
  Write(t, "jpeg-restart-24x16",
        Encode(".jpg", Picture(24, 16, CV_8UC3),
               {cv::IMWRITE_JPEG_RST_INTERVAL, 1, cv::IMWRITE_JPEG_QUALITY, 50}));
  // An EXIF segment (APP1) right after SOI holding a thumbnail's frame header of its own, which
  // the header reader must skip.
  const std::string jpeg = Encode(".jpg", Picture(8, 8, CV_8UC3), {cv::IMWRITE_JPEG_QUALITY, 50});
  const std::string thumbnail_sof =
      "\xff\xc0" + std::string("\x00\x11\x08\x10\x00\x10\x00\x03", 8) + std::string(9, '\x01');
  Write(t, "jpeg-exif-thumbnail-sof",
        jpeg.substr(0, 2) + JpegSegment(0xe1, std::string("Exif\0\0", 6) + thumbnail_sof) +
            jpeg.substr(2));

  // Edges: a header above the fuzzers' 512 x 512 budget, a header without data, a JPEG of 257
  // empty scans (above the scan limit), a JPEG that ends before its frame header.
  Write(t, "edge-png-over-budget",
        kPngSignature +
            PngChunk("IHDR",
                     BigEndian32(513) + BigEndian32(512) + std::string("\x08\x02\x00\x00\x00", 5)) +
            PngChunk("IEND", ""));
  Write(t, "edge-png-truncated", Encode(".png", Picture(16, 12, CV_8UC3)).substr(0, 50));
  std::string scans =
      "\xff\xd8" + JpegSegment(0xc0, std::string("\x08\x00\x08\x00\x08\x01\x01\x11\x00", 9));
  for (int i = 0; i < 257; ++i)
    scans += JpegSegment(0xda, std::string("\x01\x01\x00\x00\x3f\x00", 6));
  Write(t, "edge-jpeg-257-scans", scans + "\xff\xd9");
  Write(t, "edge-jpeg-no-sof", jpeg.substr(0, jpeg.find("\xff\xc0")));
}

// ---- recognition requests ----------------------------------------------------------------

std::string Cedd(int seed) {
  std::string values(144, '\0');
  for (int i = 0; i < 144; ++i) values[i] = static_cast<char>((i * seed + seed / 2) % 8);
  return values;
}

Frame CeddFrame(int seed, double azimuth) {
  Frame frame;
  frame.set_cedd(Cedd(seed));
  frame.set_azimuth_deg(azimuth);
  return frame;
}

std::string Serialized(const google::protobuf::Message& message) {
  return message.SerializeAsString();
}

void WriteSessionSeeds() {
  const std::string t = "session_request";
  const std::vector<std::pair<orbit::v1::Engine, std::string>> engines = {
      {orbit::v1::ENGINE_UNSPECIFIED, "default"},
      {orbit::v1::ENGINE_VCI, "vci"},
      {orbit::v1::ENGINE_HMM, "hmm"},
      {orbit::v1::ENGINE_VCI_HMM, "vci-hmm"},
      {orbit::v1::ENGINE_VCI_BM, "vci-bm"},
      {orbit::v1::ENGINE_VCI_W0, "vci-w0"},
      {orbit::v1::ENGINE_EIS, "eis"},
      {orbit::v1::ENGINE_SIIS, "siis"},
      {orbit::v1::ENGINE_EIIS, "eiis"}};
  for (const auto& [engine, name] : engines) {
    RecognizeRequest request;
    request.mutable_options()->set_engine(engine);
    for (int f = 0; f < 3; ++f) *request.add_frames() = CeddFrame(3 + f, 10.0 * f);
    Write(t, "engine-" + name, Serialized(request));
  }
  {
    RecognizeRequest request;  // every option set, at the end of its range
    SessionOptions& o = *request.mutable_options();
    o.set_engine(orbit::v1::ENGINE_VCI_HMM);
    o.set_top_k(100);
    o.set_window(64);
    o.set_hmm_states(16);  // 64 x 16 = 1024 cells, the server's limit
    o.set_list_length(64);
    o.set_orientation_weight(0);
    o.set_threshold(1e-300);
    o.set_variant(orbit::v1::CEDD_LIRE);
    for (int f = 0; f < 4; ++f) *request.add_frames() = CeddFrame(f + 1, -90.0 * f);
    Write(t, "options-at-limits", Serialized(request));
  }
  {
    RecognizeRequest request;  // azimuths whose difference overflows a double, with elevations
    request.mutable_options()->set_engine(orbit::v1::ENGINE_VCI);
    const double far = 1e308;
    for (double azimuth : {far, -far, 0.0, far}) {
      Frame frame = CeddFrame(5, azimuth);
      frame.set_elevation_deg(-45);
      frame.set_timestamp_us(1);
      *request.add_frames() = frame;
    }
    Write(t, "far-azimuths", Serialized(request));
  }
  {
    RecognizeRequest request;  // frames sent as images, one with a region
    Frame png;
    png.set_image(Encode(".png", Picture(12, 10, CV_8UC3)));
    png.set_azimuth_deg(5);
    *request.add_frames() = png;
    Frame jpeg;
    jpeg.set_image(Encode(".jpg", Picture(16, 16, CV_8UC1), {cv::IMWRITE_JPEG_QUALITY, 40}));
    jpeg.mutable_region()->set_x(2);
    jpeg.mutable_region()->set_y(3);
    jpeg.mutable_region()->set_width(10);
    jpeg.mutable_region()->set_height(8);
    jpeg.set_azimuth_deg(15);
    *request.add_frames() = jpeg;
    Write(t, "image-frames", Serialized(request));
  }
  {
    RecognizeRequest request;  // a bad frame after a good one: 143 values
    *request.add_frames() = CeddFrame(2, 0);
    Frame bad = CeddFrame(2, 10);
    bad.mutable_cedd()->pop_back();
    *request.add_frames() = bad;
    Write(t, "edge-short-cedd", Serialized(request));
  }
}

void WriteSettingsSeeds() {
  const std::string t = "session_settings";
  Write(t, "empty", "");
  for (int engine = 1; engine <= 8; ++engine) {
    SessionOptions o;
    o.set_engine(static_cast<orbit::v1::Engine>(engine));
    o.set_window(4);
    o.set_hmm_states(12);
    Write(t, "engine-" + std::to_string(engine), Serialized(o));
  }
  SessionOptions limits;
  limits.set_engine(orbit::v1::ENGINE_HMM);
  limits.set_top_k(100);
  limits.set_window(64);
  limits.set_hmm_states(16);
  limits.set_list_length(64);
  limits.set_orientation_weight(1e308);
  limits.set_threshold(5e-324);
  limits.set_variant(orbit::v1::CEDD_FULL);
  Write(t, "at-limits", Serialized(limits));
  limits.set_hmm_states(17);  // 64 x 17 cells: above the limit
  Write(t, "edge-hmm-cells", Serialized(limits));
  SessionOptions bad;
  bad.set_window(65);
  bad.set_orientation_weight(std::numeric_limits<double>::quiet_NaN());
  bad.set_threshold(-1);
  bad.set_engine(static_cast<orbit::v1::Engine>(9));
  Write(t, "edge-out-of-range", Serialized(bad));
}

// ---- enrollment streams ------------------------------------------------------------------

std::string Stream(const std::vector<EnrollRequest>& requests) {
  std::ostringstream out;
  for (const EnrollRequest& request : requests) {
    google::protobuf::util::SerializeDelimitedToOstream(request, &out);
  }
  return out.str();
}

EnrollRequest Header(const std::string& name, const std::string& metadata = "") {
  EnrollRequest request;
  request.mutable_header()->set_name(name);
  request.mutable_header()->set_metadata_json(metadata);
  return request;
}

EnrollRequest CeddView(int seed, double azimuth) {
  EnrollRequest request;
  request.mutable_view()->set_cedd(Cedd(seed));
  request.mutable_view()->set_azimuth_deg(azimuth);
  return request;
}

void WriteEnrollSeeds() {
  const std::string t = "enroll_stream";
  EnrollRequest typical = CeddView(4, 120);
  typical.mutable_view()->set_typical_distance(0.4);
  typical.mutable_view()->set_elevation_deg(10);
  Write(t, "descriptors", Stream({Header("mug"), CeddView(1, 0), CeddView(2, 60), typical}));

  EnrollRequest png;
  png.mutable_view()->set_image(Encode(".png", Picture(10, 8, CV_8UC3)));
  png.mutable_view()->set_azimuth_deg(0);
  png.mutable_view()->set_thumbnail("thumb");
  EnrollRequest jpeg;
  jpeg.mutable_view()->set_image(
      Encode(".jpg", Picture(16, 16, CV_8UC3), {cv::IMWRITE_JPEG_QUALITY, 40}));
  jpeg.mutable_view()->set_azimuth_deg(90);
  jpeg.mutable_view()->mutable_region()->set_width(8);
  jpeg.mutable_view()->mutable_region()->set_height(8);
  Write(t, "images", Stream({Header("box.2", R"({"shelf": [1, 2], "note": "x"})"), png, jpeg}));

  Write(t, "edge-view-first", Stream({CeddView(1, 0), Header("late")}));
  Write(t, "edge-two-headers", Stream({Header("a"), CeddView(1, 0), Header("b")}));
  Write(t, "edge-header-only", Stream({Header("lonely")}));
  EnrollRequest high = CeddView(3, 0);
  high.mutable_view()->set_elevation_deg(100);  // the server takes it, the store refuses it
  EnrollRequest far = CeddView(3, -1e308);
  far.mutable_view()->set_typical_distance(1);
  Write(t, "edge-elevation-100", Stream({Header("tall"), high, far}));
  Write(t, "edge-bad-metadata", Stream({Header("meta", "{\"a\": [[[[]]]]"), CeddView(1, 0)}));
}

// ---- CEDD ------------------------------------------------------------------------------------

// The cedd target's layout: width - 1, height - 1 (each below 128), type, flags,
// [x, y, w, h,] pixels.
std::string CeddInput(int width, int height, int type, int flags, const std::string& roi,
                      const std::string& pixels) {
  return std::string{static_cast<char>(width - 1), static_cast<char>(height - 1),
                     static_cast<char>(type), static_cast<char>(flags)} +
         roi + pixels;
}

void WriteCeddSeeds() {
  const std::string t = "cedd";
  const cv::Mat picture = Picture(16, 16, CV_8UC4);
  const std::string pixels(reinterpret_cast<const char*>(picture.data), 16 * 16 * 4);
  // type 0 grey, 1 BGR, 2 BGRA, 3 and 4 refused; flags: 1 full variant, 2 region, 4 view.
  Write(t, "grey-1x1", CeddInput(1, 1, 0, 0, "", "\x80"));
  Write(t, "grey-1x9-full", CeddInput(1, 9, 0, 1, "", pixels.substr(0, 9)));
  Write(t, "bgr-16x16", CeddInput(16, 16, 1, 0, "", pixels.substr(0, 16 * 16 * 3)));
  Write(t, "bgr-16x16-full", CeddInput(16, 16, 1, 1, "", pixels.substr(0, 16 * 16 * 3)));
  Write(t, "bgra-40x39-view", CeddInput(40, 39, 2, 4, "", pixels));
  Write(t, "bgr-80x80-region", CeddInput(80, 80, 1, 2, std::string("\x05\x07\x32\x28", 4), pixels));
  Write(t, "bgr-120x80-full-region-view",
        CeddInput(120, 80, 1, 7, std::string("\x00\x00\x77\x50", 4), pixels));
  Write(t, "grey-128x128", CeddInput(128, 128, 0, 0, "", pixels.substr(0, 1000)));
  Write(t, "edge-region-outside",
        CeddInput(10, 10, 1, 2, std::string("\x08\x08\x03\x03", 4), pixels));
  Write(t, "edge-region-empty",
        CeddInput(10, 10, 1, 2, std::string("\x01\x01\x00\x03", 4), pixels));
  Write(t, "edge-16bit", CeddInput(4, 4, 4, 0, "", pixels.substr(0, 96)));
}

// ---- manifests -------------------------------------------------------------------------------

void WriteManifestSeeds() {
  const std::string t = "manifest";
  const std::string nul(1, '\0');
  Write(t, "plain",
        "path,object,azimuth\nimages/a0.png,cup,0\nimages/a1.png,cup,90\n/abs/b0.png,bowl,359.5\n");
  Write(t, "elevation-quotes-crlf",
        "azimuth, object ,path,elevation\r\n-30,\"mug, red\",\"a \"\"b\"\".png\",12.5\r\n"
        "\r\n390,plate,p.png,\r\n1e-300,plate,q.png,-90\r\n");
  Write(t, "selection",
        "1-2" + nul + "3" + nul + "path,object,azimuth\na,o1,0\nb,o2,10\nc,o3,20\nd,o1,30\n");
  Write(t, "selection-ranges",
        " 1 , 3-4,2" + nul + "" + nul + "path,object,azimuth\na,o1,0\nb,o2,10\nc,o3,20\nd,o4,30\n");
  Write(t, "edge-unknown-column", "path,object,azimuth,tilt\na,b,1,2\n");
  Write(t, "edge-bad-azimuth", "path,object,azimuth\na,b,nan\n");
  Write(t, "edge-open-quote", "path,object,azimuth\n\"a,b,1\n");
  Write(t, "edge-overlap",
        "1-3" + nul + "2" + nul + "path,object,azimuth\na,o1,0\nb,o2,10\nc,o3,5\n");
  Write(t, "edge-large-range", "1-999999" + nul + "" + nul + "path,object,azimuth\na,o1,0\n");
}

// ---- orientation logs ------------------------------------------------------------------------

void WriteOrientationLogSeeds() {
  const std::string t = "orientation_log";
  Write(t, "timestamps", "timestamp_ms,azimuth_deg\n0,350.5\n33.3,355\n66.7,2.25\n100,10\n");
  Write(t, "elevation-gap-comments",
        "# walk\ntimestamp_ms,azimuth_deg,elevation_deg\n\n0,-20,5\n20,-18,5.5\n900,70,-30\r\n");
  Write(t, "frame-index", "frame_index,azimuth_deg\n0,359\n1,1\n3,7\n");
  Write(t, "no-header-box", "12,40,100,80\n0,0\n500,720\n");
  Write(t, "edge-backwards", "timestamp_ms,azimuth_deg\n0,1\n50,2\n40,3\n");
  Write(t, "edge-non-finite", "0,1\n10,nan\n20,inf\n");
  Write(t, "edge-huge", "0,1e308\n1e308,-1e308,90\n");
  Write(t, "edge-fields", "timestamp_ms,azimuth_deg\n0,1,2,3\n1,\n,\n");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: " << argv[0] << " CORPUS_FOLDER (fuzz/corpus)\n";
    return 1;
  }
  corpus_root = argv[1];
  WriteImageSeeds();
  WriteSessionSeeds();
  WriteSettingsSeeds();
  WriteEnrollSeeds();
  WriteCeddSeeds();
  WriteManifestSeeds();
  WriteOrientationLogSeeds();
  return 0;
}
