// RunServerEvaluation: `orbit eval --server --queries`. A user's captured query sequences
// (evaluation/dataset.h, ReadQueryCaptures) recognised by a running Orbit server, each streamed
// as a recognition session through the client library exactly as a device streams one
// (client/recognition_session.h), and counted into the report RunCaptureEvaluation gives for a
// local model set (evaluation/evaluation_runner.h), so that one report code writes both
// (evaluation/evaluation_report.h, evaluation/recognition_report.h).
//
// The model set is the server's: a query whose object bears the name of an object the server
// holds is known, and right when that object is its top-1 candidate; a query of any other
// object is an unknown query, right when answered UNKNOWN. Every session runs with the
// server's defaults (ServerInfo's session_defaults) and the connection's token; the report has
// one method, named after them (ServerMethodName), on the server's descriptor variant, and one
// distortion, df: the frames as captured.
//
// Thread safety: may be called from any thread; runs its sessions one after another.
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "client/connection.h"
#include "client/object_region.h"
#include "evaluation/dataset.h"
#include "evaluation/evaluation_runner.h"
#include "orbit/v1/models.pb.h"

namespace orbit {

struct ServerEvaluationOptions {
  std::vector<int> query_lengths = EvaluationOptions{}.query_lengths;  // n (1..kMaxWindow)
  // false: the frames carry no azimuth, as from a device without an orientation sensor.
  bool use_orientation = true;
  // The object's box in each frame (ReadBoxes' keys, matched as AttachBoxes matches paths): each
  // frame is described in its box grown by box_margin (ObjectRegion, client/object_region.h), as
  // `orbit recognize --boxes` describes it. Empty: the whole frames.
  std::map<std::string, ImageBox> boxes;
  double box_margin = kDefaultBoxMargin;
  // Called after each sequence with the stage ("sessions"), sequences done and sequences in
  // all. May be empty.
  std::function<void(std::string_view stage, std::size_t done, std::size_t total)> progress;
};

// The report's method for a server with `info`: "server (product)" when the defaults ServerInfo
// shows are the product pipeline's (core/engines/product_pipeline.h: its engine, its variant and
// its engine's options), else "server (ENGINE)" with the default engine's name
// (api/engines/engine_names.h).
std::string ServerMethodName(const v1::ServerInfoResponse& info);

// Asks the server behind `connection` (its address is the report's ServerDescription) for its
// objects, then recognises every sequence of `captures`: one session per sequence, sent its
// first max(n) frames (all of a shorter sequence) and read at every n; a sequence shorter than
// n is not counted at n. The report's cells, verdicts, counts and query totals are as
// RunCaptureEvaluation's; its times are the server's processing times (SessionUpdate's
// processing_time_us, summed over a query's n frames) and, as trial_seconds, the wall-clock
// time of all sessions. Verdicts carry no unknown statistic nor p-value (NaN): a server's
// updates state neither.
//
// Throws std::invalid_argument for no n or an n outside 1..kMaxWindow, a sequence that shows
// two objects (GroupCaptureSequences), a frame without a box when `boxes` is not empty or a box
// not inside its frame (naming the box's origin); std::runtime_error naming the row of a frame
// whose image cannot be read; RpcError (client/rpc_error.h) when the server cannot be reached,
// refuses the token or ends a session.
EvaluationReport RunServerEvaluation(const Connection& connection,
                                     const std::vector<CaptureFrame>& captures,
                                     const ServerEvaluationOptions& options);

}  // namespace orbit
