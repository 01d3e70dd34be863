#include "evaluation/server_evaluation.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <thread>

#include "api/conversion.h"
#include "api/engines/conversion.h"
#include "api/engines/engine_names.h"
#include "client/models_client.h"
#include "client/recognition_session.h"
#include "client/rpc_error.h"
#include "core/decision/rejection.h"
#include "core/engines/product_pipeline.h"

namespace orbit {
namespace {

using Clock = std::chrono::steady_clock;

void ValidateQueryLengths(const std::vector<int>& ns) {
  if (ns.empty()) throw std::invalid_argument("no query length n");
  for (int n : ns) {
    if (n < 1 || n > kMaxWindow) {
      throw std::invalid_argument("n = " + std::to_string(n) + " is outside 1.." +
                                  std::to_string(kMaxWindow));
    }
  }
}

// The session defaults `d` in words, as the report states what every query ran with.
std::string DescribeDefaults(const v1::SessionOptions& d) {
  std::ostringstream out;
  out << "engine " << SessionEngineName(d.engine()) << ", window " << d.window() << ", N_L "
      << d.list_length() << ", w " << d.orientation_weight() << ", HMM states " << d.hmm_states()
      << ", rejection ";
  const std::optional<RejectionRule> rule = FromProtoRejection(d.rejection());
  if (!rule) {
    out << "unstated";
  } else if (*rule == RejectionRule::kCalibrated) {
    out << RejectionRuleName(*rule) << " (false-accept rate " << d.false_accept_rate() << ")";
  } else {
    out << RejectionRuleName(*rule) << " (Th " << d.threshold() << ")";
  }
  return out.str();
}

// Whether a server's ServerInfo shows the product pipeline's defaults. The options a session
// cannot ask for (the HMM's sharpening, the nearest-view blend, the move rule) are not shown;
// the server always runs the product's (server/session_settings.h).
bool RunsProduct(const v1::ServerInfoResponse& info) {
  const v1::SessionOptions& d = info.session_defaults();
  const ProductPipeline& product = Product();
  const EngineOptions& p = product.options;
  return info.variant() == ToProtoVariant(product.variant) &&
         d.engine() == ProductSessionEngine() && d.window() == p.window &&
         d.list_length() == p.list_length && d.orientation_weight() == p.orientation_weight &&
         d.hmm_states() == p.hmm_states && d.rejection() == ToProtoRejection(p.rejection) &&
         d.false_accept_rate() == p.false_accept_rate && d.threshold() == p.threshold;
}

// The first `count` frames of `sequence` sent as one session with the server's defaults, paced
// to its frame-rate limit; returns their updates in frame order. `frames` are the captures as
// dataset images (their boxes attached), in the captures' order.
std::vector<v1::SessionUpdate> RecogniseSequence(const Connection& connection,
                                                 const std::vector<CaptureFrame>& captures,
                                                 const std::vector<DatasetImage>& frames,
                                                 const CaptureSequence& sequence, std::size_t count,
                                                 bool use_orientation) {
  auto session = RecognitionSession::Open(connection, RecognitionOptions{});
  Clock::time_point next_allowed = Clock::now();
  try {
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t f = sequence.frames[k];
      const cv::Mat image = ReadCaptureImage(captures[f]);
      const std::optional<cv::Rect> region =
          frames[f].box ? std::optional<cv::Rect>(DescribedRegion(frames[f], image.size()))
                        : std::nullopt;
      std::this_thread::sleep_until(next_allowed);
      next_allowed = Clock::now() + session->min_frame_interval();
      session->Push(image, use_orientation ? captures[f].azimuth : std::nullopt, region);
    }
  } catch (const RpcError&) {
    // The session ended early; Close() reports why.
  }
  const grpc::Status status = session->Close();
  if (!status.ok()) throw RpcError("Session", status);
  std::vector<std::optional<v1::SessionUpdate>> by_frame(count);
  while (std::optional<v1::SessionUpdate> update = session->NextUpdate()) {
    const auto index = static_cast<std::size_t>(update->frame_index());
    if (index < count) by_frame[index] = std::move(*update);
  }
  std::vector<v1::SessionUpdate> updates;
  for (std::optional<v1::SessionUpdate>& update : by_frame) {
    if (!update) {
      throw std::runtime_error("sequence \"" + sequence.name + "\": the server answered " +
                               std::to_string(updates.size()) + " of its " + std::to_string(count) +
                               " frames");
    }
    updates.push_back(std::move(*update));
  }
  return updates;
}

// The verdict of `update` for a query of `object`, whose right answer is the object with id
// `expected`, or UNKNOWN when `expected` is 0 (no object of the query's name on the server).
QueryVerdict Judge(const v1::SessionUpdate& update, std::string_view object,
                   std::int64_t expected) {
  QueryVerdict verdict;
  verdict.known = expected != 0;
  verdict.hit =
      verdict.known && update.candidates_size() > 0 && update.candidates(0).id() == expected;
  verdict.object = object;
  if (update.candidates_size() > 0) verdict.answer = update.candidates(0).name();
  verdict.decision = FromProtoDecision(update.decision());
  verdict.unknown_statistic = std::numeric_limits<double>::quiet_NaN();
  verdict.unknown_p_value = std::numeric_limits<double>::quiet_NaN();
  verdict.confidence = update.confidence();
  return verdict;
}

}  // namespace

std::string ServerMethodName(const v1::ServerInfoResponse& info) {
  return "server (" +
         (RunsProduct(info) ? std::string(kProductMethod)
                            : SessionEngineName(info.session_defaults().engine())) +
         ")";
}

EvaluationReport RunServerEvaluation(const Connection& connection,
                                     const std::vector<CaptureFrame>& captures,
                                     const ServerEvaluationOptions& options) {
  ValidateQueryLengths(options.query_lengths);
  const std::vector<CaptureSequence> sequences = GroupCaptureSequences(captures);
  const std::vector<DatasetImage> frames =
      CaptureImages(captures, options.boxes, options.box_margin);

  ModelsClient models(connection);
  const v1::ServerInfoResponse info = models.ServerInfo();
  std::map<std::string, std::int64_t> id_of;  // the server's objects by name
  for (const v1::ObjectInfo& object : models.ListAllObjects()) id_of[object.name()] = object.id();

  EvaluationReport report;
  report.server = ServerDescription{connection.options().address, info.version(),
                                    static_cast<std::size_t>(info.view_count()),
                                    DescribeDefaults(info.session_defaults()), RunsProduct(info)};
  report.known_objects = id_of.size();
  report.images = captures.size();
  report.query_sequences = sequences.size();
  report.query_frames = captures.size();
  report.threads = 1;
  report.use_orientation = options.use_orientation;
  std::set<std::string> unknown_objects;
  for (const CaptureSequence& sequence : sequences) {
    if (!id_of.contains(sequence.object)) unknown_objects.insert(sequence.object);
  }
  report.unknown_objects = unknown_objects.size();

  const std::string method = ServerMethodName(info);
  const DescriptorVariant variant = FromProtoVariant(info.variant());
  for (int n : options.query_lengths) {
    EvaluationCell& cell = report.cells.emplace_back();
    cell.method = method;
    cell.variant = variant;
    cell.distortion = "df";
    cell.n = n;
  }

  // One session per sequence, read after each n-th frame, rather than a fresh session per n:
  // a session answers frame k from frames 0..k alone, in the order they were sent (the server
  // cannot see later ones), so its update after frame n is what a user's session of just those
  // n frames receives, and each frame is sent once instead of once per n.
  const auto largest_n = static_cast<std::size_t>(
      *std::max_element(options.query_lengths.begin(), options.query_lengths.end()));
  const Clock::time_point start = Clock::now();
  for (std::size_t s = 0; s < sequences.size(); ++s) {
    const CaptureSequence& sequence = sequences[s];
    const std::vector<v1::SessionUpdate> updates =
        RecogniseSequence(connection, captures, frames, sequence,
                          std::min(sequence.frames.size(), largest_n), options.use_orientation);
    const auto found = id_of.find(sequence.object);
    const std::int64_t expected = found == id_of.end() ? 0 : found->second;
    for (EvaluationCell& cell : report.cells) {
      const auto n = static_cast<std::size_t>(cell.n);
      if (updates.size() < n) continue;
      double seconds = 0;
      for (std::size_t k = 0; k < n; ++k) seconds += updates[k].processing_time_us() * 1e-6;
      cell.Add(Judge(updates[n - 1], sequence.object, expected), seconds);
    }
    if (options.progress) options.progress("sessions", s + 1, sequences.size());
  }
  report.trial_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return report;
}

}  // namespace orbit
