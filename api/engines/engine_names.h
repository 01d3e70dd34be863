// The engines as the API names them: proto/orbit/v1/recognition.proto's Engine values and the
// engines' names (core/engines/engine_registry.h), converted both ways, for the server (what a
// v1::Engine runs), the command line (--engine) and reports.
//
// A value's name is the value's, lower-cased, without "ENGINE_" and with '-' for '_'
// (ENGINE_VCI_HMM: "vci-hmm"). tests/api/engines/engine_names_test.cc checks that every value
// names an engine of the registry and every engine has a value.
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

// Whether `engine` keeps an HMM (EngineKind::keeps_hmm: ENGINE_HMM, ENGINE_VCI_HMM), whose
// memory grows with window x states (server/session_settings.h bounds it); false for
// ENGINE_UNSPECIFIED or a value this build does not know.
bool RunsHmm(v1::Engine engine);

}  // namespace orbit
