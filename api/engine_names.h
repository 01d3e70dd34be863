// The engines a recognition session can run, by name: the one list of names with their parsing,
// for the server (what a v1::Engine runs), the command line (--engine) and reports.
//
// The names are those of proto/orbit/v1/recognition.proto's Engine values, lower-cased, without
// "ENGINE_" and with '-' for '_': vci, hmm, vci-hmm, vci-bm, vci-w0, eis, siis, eiis. Every one
// but vci-hmm is the name of one engine of core/engines/recognition_engine.h (CreateEngine); vci-hmm runs
// vci and hmm side by side (server/session_engine.h). tests/api/engine_names_test.cc checks that
// the proto's engines and core's agree.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "orbit/v1/recognition.pb.h"

namespace orbit {

// The name of `engine`; "" for ENGINE_UNSPECIFIED or a value this build does not know.
std::string SessionEngineName(v1::Engine engine);

// Every engine's name, in the proto's order (vci first).
std::vector<std::string> SessionEngineNames();

// The engine called `name`. Throws std::invalid_argument listing the names for any other text.
v1::Engine ParseSessionEngine(std::string_view name);

// The session engine that runs the product pipeline's engine (core/engines/product_pipeline.h): the
// default of a session that asks for none.
v1::Engine ProductSessionEngine();

// The engines of core/engines/recognition_engine.h that `engine` runs: one name, two for ENGINE_VCI_HMM,
// none for ENGINE_UNSPECIFIED or an unknown value.
std::vector<std::string_view> CoreEngineNames(v1::Engine engine);

// Whether `engine` keeps an HMM (ENGINE_HMM, ENGINE_VCI_HMM), whose memory grows with
// window x states (server/session_settings.h bounds it).
bool RunsHmm(v1::Engine engine);

}  // namespace orbit
