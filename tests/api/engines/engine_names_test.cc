// The engines' names (api/engines/engine_names.h): the proto's Engine values and core's engines
// agree, and a name read from the command line maps to the engine a server runs.
#include "api/engines/engine_names.h"

#include <stdexcept>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/engines/engine_registry.h"

namespace orbit {
namespace {

using ::testing::ElementsAre;

TEST(EngineNamesTest, NamesComeFromTheProtoInItsOrder) {
  EXPECT_THAT(SessionEngineNames(),
              ElementsAre("vci", "hmm", "vci-hmm", "vci-bm", "vci-w0", "eis", "siis", "eiis"));
  EXPECT_EQ(SessionEngineName(v1::ENGINE_VCI_W0), "vci-w0");
  EXPECT_EQ(SessionEngineName(v1::ENGINE_UNSPECIFIED), "");
  EXPECT_EQ(SessionEngineName(static_cast<v1::Engine>(99)), "");
}

TEST(EngineNamesTest, ParseIsTheInverseAndRefusesOtherNamesListingTheKnownOnes) {
  for (const std::string& name : SessionEngineNames()) {
    EXPECT_EQ(SessionEngineName(ParseSessionEngine(name)), name);
  }
  EXPECT_EQ(ParseSessionEngine("vci-hmm"), v1::ENGINE_VCI_HMM);
  for (const char* bad : {"", "unspecified", "VCI", "vci+hmm", "hmm "}) {
    try {
      ParseSessionEngine(bad);
      ADD_FAILURE() << "accepted \"" << bad << "\"";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()),
                "unknown engine \"" + std::string(bad) +
                    "\" (engines: vci, hmm, vci-hmm, vci-bm, vci-w0, eis, siis, eiis)");
    }
  }
}

TEST(EngineNamesTest, EveryEngineHasAWireValueAndEveryValueAnEngine) {
  // Each engine CreateEngine builds is reachable from the API, and every API engine is one of
  // the registry's: the two cannot drift apart unnoticed.
  for (std::string_view name : EngineNames()) {
    EXPECT_EQ(SessionEngineName(ParseSessionEngine(name)), name);
  }
  for (const std::string& name : SessionEngineNames()) {
    EXPECT_EQ(CreateEngine(name)->name(), name);
  }
  EXPECT_EQ(SessionEngineNames().size(), EngineNames().size());
}

TEST(EngineNamesTest, RunsHmmForTheEnginesThatKeepOne) {
  EXPECT_TRUE(RunsHmm(v1::ENGINE_HMM));
  EXPECT_TRUE(RunsHmm(v1::ENGINE_VCI_HMM));
  for (v1::Engine engine : {v1::ENGINE_VCI, v1::ENGINE_VCI_BM, v1::ENGINE_VCI_W0, v1::ENGINE_EIS,
                            v1::ENGINE_SIIS, v1::ENGINE_EIIS, v1::ENGINE_UNSPECIFIED}) {
    EXPECT_FALSE(RunsHmm(engine)) << SessionEngineName(engine);
  }
}

}  // namespace
}  // namespace orbit
