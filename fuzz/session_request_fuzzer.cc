// Fuzz target: a recognition request read and served as the Recognition service serves it
// (server/recognition_service.cc, Recognize; a Session stream does the same per message): the
// options resolved against the server's defaults and limits (server/session_settings.h), each
// frame read by ToQueryFrame (server/request_reading.h: DescriptorFromWire of api/conversion.h
// for `cedd`; the image budget and the decode for `image`), observed by the session's engine on
// a small index, and its update converted for the wire.
//
// Input: a serialized orbit.v1.RecognizeRequest (options and frames); bytes that do not parse are
// skipped, as gRPC refuses them. The seeds (corpus/session_request/) hold descriptor frames,
// image frames, every engine and options at their limits.
//
// Checked beyond "no crash": a frame that ToQueryFrame accepts holds 144 values in 0..7 and a
// finite azimuth; an update ranks at most top_k objects of the index with finite scores.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <memory>
#include <vector>

#include "api/conversion.h"
#include "api/engines/conversion.h"
#include "core/decision/rejection_calibration.h"
#include "core/index/view_index.h"
#include "fuzz/fuzz_support.h"
#include "orbit/v1/recognition.pb.h"
#include "server/request_reading.h"
#include "server/session_engine.h"
#include "server/session_settings.h"

namespace orbit {
namespace {

constexpr auto kVariant = DescriptorVariant::kCeddLire;  // the server's default

// Three objects of twelve views each, every 30 degrees, with descriptors from a fixed
// pseudo-random sequence and typical distances (so that decisions are made), searched by
// kd-tree as `orbit serve` searches.
std::shared_ptr<const ViewIndexSnapshot> SmallIndex() {
  std::uint32_t state = 12345;
  const auto next = [&state] {
    state = state * 1664525u + 1013904223u;
    return state >> 24;
  };
  std::vector<ObjectModel> models;
  for (ObjectId id = 1; id <= 3; ++id) {
    ObjectModel model{id, "object" + std::to_string(id), kVariant, {}};
    for (int v = 0; v < 12; ++v) {
      ModelView view;
      for (std::uint8_t& value : view.descriptor) value = static_cast<std::uint8_t>(next() % 8);
      view.azimuth = 30.0 * v;
      view.typical_distance = 0.2 + 0.05 * static_cast<double>(id);
      model.views.push_back(view);
    }
    models.push_back(std::move(model));
  }
  static ViewIndex index(std::move(models), {.search = SearchMode::kKdTree});
  return index.Snapshot();
}

}  // namespace
}  // namespace orbit

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace orbit;
  static const std::shared_ptr<const ViewIndexSnapshot> index = SmallIndex();
  static const server::ServerLimits limits = fuzz::FuzzLimits();
  static const server::SessionSettings defaults;
  static const auto calibration =
      std::make_shared<const RejectionCalibration>(RejectionCalibration::FromIndex(*index));

  fuzz::SilenceProtobufLogs();
  v1::RecognizeRequest request;
  if (!request.ParseFromArray(data, static_cast<int>(size))) return 0;
  server::SessionSettings settings;
  if (!server::ResolveSessionSettings(request.options(), defaults, kVariant, limits, &settings)
           .ok()) {
    return 0;
  }
  const std::unique_ptr<RecognitionEngine> engine = server::CreateSessionEngine(settings);
  engine->SetCalibration(calibration);
  for (const v1::Frame& frame : request.frames()) {
    QueryFrame query;
    if (!server::ToQueryFrame(frame, kVariant, limits, &query).ok()) return 0;
    ORBIT_FUZZ_CHECK(!query.azimuth || std::isfinite(*query.azimuth));
    ORBIT_FUZZ_CHECK(query.descriptor.variant == kVariant);
    for (std::uint8_t value : query.descriptor.values)
      ORBIT_FUZZ_CHECK(value <= kDescriptorMaxValue);
    FrameUpdate update;
    try {
      update = engine->Observe(index, query);
    } catch (const std::exception&) {
      return 0;  // the service answers with the exception's status (StatusFromException)
    }
    ORBIT_FUZZ_CHECK(update.ranking.size() <= static_cast<std::size_t>(settings.options.top_k));
    ORBIT_FUZZ_CHECK(update.confidence >= 0 && update.confidence <= 1);
    ORBIT_FUZZ_CHECK(!update.pose || (update.pose->azimuth >= 0 && update.pose->azimuth < 360 &&
                                      update.pose->spread >= 0 && update.pose->spread <= 180));
    for (const RankedObject& ranked : update.ranking) {
      ORBIT_FUZZ_CHECK(index->Find(ranked.object) != nullptr);
      ORBIT_FUZZ_CHECK(std::isfinite(ranked.score));
    }
    const v1::SessionUpdate wire = ToSessionUpdate(update, *index);
    ORBIT_FUZZ_CHECK(wire.candidates_size() == static_cast<int>(update.ranking.size()));
  }
  return 0;
}
